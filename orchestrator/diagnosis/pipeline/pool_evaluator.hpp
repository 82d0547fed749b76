// The service's worker pool as the diagnosis's Evaluator: every run of a batch becomes an ordinary
// job of the campaign, run as one batch (orch::run_batch, shared with calibration). The job cache
// answers runs already made (by this diagnosis before a restart, or by another diagnosis of the
// same template) at once.
#pragma once

#include <cstdint>
#include <stop_token>

#include <nlohmann/json.hpp>

#include "engine/spec.hpp"
#include "orchestrator/diagnosis/analysis/evaluator.hpp"
#include "orchestrator/diagnosis/analysis/observations.hpp"
#include "orchestrator/diagnosis/pipeline/jobs.hpp"
#include "orchestrator/job_service.hpp"

namespace rockcal::diagnosis {

class PoolEvaluator : public Evaluator {
 public:
  PoolEvaluator(orch::JobService& service, std::int64_t campaign_id, nlohmann::json job_template,
                std::vector<Target> targets, std::stop_token stop);

  // Throws DiagnosisCancelled when the campaign is cancelled or the server stops.
  std::vector<RunOutcome> run_batch(std::span<const RunRequest> requests) override;

 private:
  orch::JobService& service_;
  std::int64_t campaign_id_;
  nlohmann::json job_template_;
  JobSpec model_;
  std::vector<Target> targets_;
  RunPlan plan_;
  std::stop_token stop_;
};

}  // namespace rockcal::diagnosis
