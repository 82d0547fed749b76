// A campaign's state and progress, derived from its jobs (and its driver, if it has one); never
// stored on its own.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "db/store.hpp"

namespace rockcal::orch {

struct CampaignStatus {
  std::string state;  // queued | running | succeeded | failed | cancelled
  db::StateCounts counts;
  // 0..1 of the work done: of the jobs' (a sweep), or of the driver's progress model while its live
  // summary carries one (a calibration's evaluations of its budget, a diagnosis's jobs of the
  // ones it plans), which never goes backwards as the driver adds jobs.
  double fraction = 0;
  std::optional<double> eta_seconds;  // of the jobs queued now; unknown until some job has run
  // The running driver's progress model as of now (orchestrator/progress_model.hpp): a
  // calibration's as its summary states it, a diagnosis's with its jobs done counted now and the
  // ETA of its planned jobs left; null for a sweep and once the driver has ended (its report
  // carries the finished model).
  nlohmann::json model;
};

// `workers`: how many jobs run at once, for the ETA.
CampaignStatus campaign_status(db::Store& store, const db::CampaignRow& campaign, int workers);

// The state alone, from counts (exposed for tests).
std::string derive_state(const db::StateCounts& c, const db::CampaignRow& campaign);

bool is_terminal_job_state(const std::string& state);

}  // namespace rockcal::orch
