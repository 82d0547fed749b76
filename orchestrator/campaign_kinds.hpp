// Campaign kinds. Each kind turns a request into the jobs to store (validating all of it first) and
// may bring a driver: a thread that submits further jobs as results come in (calibration).
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <stop_token>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "db/records.hpp"

namespace rockcal::orch {

class JobService;

struct Limits {
  std::size_t max_jobs_per_campaign = 10000;
};

struct CampaignPlan {
  std::string name;
  std::vector<db::NewJob> jobs;  // created with the campaign, all in one transaction
};

// What a driver thread gets. It runs jobs on the service's pool through the one job runner
// (orch::PoolRunner over `service`, orchestrator/pool_runner.hpp) and should return soon after
// `stop` is requested (server shutdown or campaign cancelled).
struct DriverContext {
  JobService& service;
  std::int64_t campaign_id;
  nlohmann::json request;
  std::stop_token stop;
};

struct CampaignKind {
  std::string name;
  // Validates the whole request and returns the initial jobs; throws RequestError naming the field.
  std::function<CampaignPlan(const nlohmann::json& request, const Limits& limits)> plan;
  // Empty for kinds whose jobs are all known up front (sweep). Returns the summary JSON to store.
  std::function<nlohmann::json(DriverContext& ctx)> driver;
  // Optional: a self-contained HTML page of a campaign's summary (the diagnosis report), served at
  // GET /api/v1/campaigns/{id}/report.html. Empty for kinds without one.
  std::function<std::string(const nlohmann::json& summary)> report_html;
};

class KindRegistry {
 public:
  void add(CampaignKind kind) { kinds_[kind.name] = std::move(kind); }
  const CampaignKind* find(const std::string& name) const {
    auto it = kinds_.find(name);
    return it == kinds_.end() ? nullptr : &it->second;
  }
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& [name, kind] : kinds_) out.push_back(name);
    return out;
  }

 private:
  std::map<std::string, CampaignKind> kinds_;
};

}  // namespace rockcal::orch
