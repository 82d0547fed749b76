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
  double fraction = 0;                // 0..1 of the jobs' work done
  std::optional<double> eta_seconds;  // unknown until some job has run
};

// `workers`: how many jobs run at once, for the ETA.
CampaignStatus campaign_status(db::Store& store, const db::CampaignRow& campaign, int workers);

// The state alone, from counts (exposed for tests).
std::string derive_state(const db::StateCounts& c, const db::CampaignRow& campaign);

bool is_terminal_job_state(const std::string& state);

}  // namespace rockcal::orch
