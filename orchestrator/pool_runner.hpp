// The service's worker pool as the JobRunner: a batch is jobs of the campaign. Every job is
// submitted before any is waited for, so the pool runs them in parallel; equal specs within a
// batch are submitted once; the job cache answers runs already made (by this campaign before a
// restart, or by another of the same template) at once.
#pragma once

#include <cstdint>
#include <stop_token>

#include "orchestrator/job_runner.hpp"
#include "orchestrator/job_service.hpp"

namespace rockcal::orch {

class PoolRunner : public JobRunner {
 public:
  PoolRunner(JobService& service, std::int64_t campaign_id, std::stop_token stop);

  // std::nullopt when `stop` was requested or a job was cancelled (the campaign is being
  // cancelled).
  std::optional<std::vector<Realisation>> run(const std::vector<nlohmann::json>& jobs) override;

 private:
  JobService& service_;
  std::int64_t campaign_id_;
  std::stop_token stop_;
};

}  // namespace rockcal::orch
