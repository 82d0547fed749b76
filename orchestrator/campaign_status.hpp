// A campaign's state and progress, derived from its jobs (and its driver, if it has one); never
// stored on its own.
#pragma once

#include <optional>
#include <string>

#include "db/store.hpp"

namespace rockcal::orch {

struct CampaignStatus {
  std::string state;  // queued | running | succeeded | failed | cancelled
  db::StateCounts counts;
  // 0..1 of the work done: of the jobs' (a sweep), or of the driver's own progress when its live
  // summary states one (a calibration's evaluations of its budget, a diagnosis's phases), which
  // never goes backwards as the driver adds jobs.
  double fraction = 0;
  std::optional<double> eta_seconds;  // unknown until some job has run
};

// `workers`: how many jobs run at once, for the ETA.
CampaignStatus campaign_status(db::Store& store, const db::CampaignRow& campaign, int workers);

// The state alone, from counts (exposed for tests).
std::string derive_state(const db::StateCounts& c, const db::CampaignRow& campaign);

bool is_terminal_job_state(const std::string& state);

}  // namespace rockcal::orch
