#include "orchestrator/pool_runner.hpp"

#include <map>
#include <string>

#include "orchestrator/realisations.hpp"

namespace rockcal::orch {

PoolRunner::PoolRunner(JobService& service, std::int64_t campaign_id, std::stop_token stop)
    : service_(service), campaign_id_(campaign_id), stop_(stop) {}

std::optional<std::vector<Realisation>> PoolRunner::run(const std::vector<nlohmann::json>& jobs) {
  // nlohmann::json objects keep keys sorted, so dump() is one key per spec.
  std::map<std::string, std::int64_t> job_of_spec;
  std::vector<std::int64_t> ids;
  for (const nlohmann::json& job : jobs) {
    auto [it, fresh] = job_of_spec.try_emplace(job.dump(), 0);
    if (fresh) it->second = service_.submit_job(campaign_id_, job, stop_);
    if (stop_.stop_requested()) return std::nullopt;  // perhaps before the job was stored
    ids.push_back(it->second);
  }
  std::map<std::int64_t, JobOutcome> outcome_of;
  for (const auto& [spec, id] : job_of_spec) {
    JobOutcome outcome = service_.wait_job(id, stop_);
    if (stop_.stop_requested() || outcome.state == db::kCancelled) return std::nullopt;
    outcome_of.emplace(id, std::move(outcome));
  }
  std::vector<Realisation> runs;
  for (std::size_t i = 0; i < jobs.size(); ++i)
    runs.push_back(realisation(outcome_of.at(ids[i]), jobs[i]));
  return runs;
}

}  // namespace rockcal::orch
