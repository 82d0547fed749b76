// A batch of jobs on the service's pool: the one way a campaign (calibration, diagnosis) runs its
// jobs. Every job is submitted before any is waited for, so the pool runs them in parallel; equal
// specs within a batch are submitted once; the job cache answers runs already made (by this
// campaign before a restart, or by another of the same template) at once.
#pragma once

#include <cstdint>
#include <optional>
#include <stop_token>
#include <vector>

#include <nlohmann/json.hpp>

#include "orchestrator/job_service.hpp"

namespace rockcal::orch {

// Each job's outcome, in order; std::nullopt when `stop` was requested or a job was cancelled
// (the campaign is being cancelled: the caller stops rather than read partial results).
std::optional<std::vector<JobOutcome>> run_batch(JobService& service, std::int64_t campaign_id,
                                                 const std::vector<nlohmann::json>& jobs,
                                                 std::stop_token stop);

}  // namespace rockcal::orch
