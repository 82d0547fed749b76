// The diagnosis's Evaluator over the one runner (orchestrator/job_runner.hpp, shared with
// calibration and twins): every run of a batch becomes an engine job (job_for), all run as one
// batch, and each target reads its observable off its run. On the service's pool
// (orch::PoolRunner) the job cache answers runs already made (by this diagnosis before a restart,
// or by another diagnosis of the same template) at once.
#pragma once

#include <nlohmann/json.hpp>

#include "engine/spec.hpp"
#include "orchestrator/diagnosis/analysis/evaluator.hpp"
#include "orchestrator/diagnosis/analysis/observations.hpp"
#include "orchestrator/diagnosis/pipeline/jobs.hpp"
#include "orchestrator/job_runner.hpp"

namespace rockcal::diagnosis {

class RunnerEvaluator : public Evaluator {
 public:
  RunnerEvaluator(orch::JobRunner& runner, nlohmann::json job_template,
                  std::vector<Target> targets);

  // Throws DiagnosisCancelled when the runner is cancelled (the campaign, or the server stops).
  std::vector<RunOutcome> run_batch(std::span<const RunRequest> requests) override;
  std::vector<RunOutcome> run_on(std::span<const RunRequest> requests,
                                 const std::vector<Target>& targets) override;

 private:
  orch::JobRunner& runner_;
  nlohmann::json job_template_;
  JobSpec model_;
  std::vector<Target> targets_;
};

}  // namespace rockcal::diagnosis
