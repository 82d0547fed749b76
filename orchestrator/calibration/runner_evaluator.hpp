// The calibration's Evaluator over the one runner (orchestrator/job_runner.hpp): each request of a
// batch becomes the UCT and BTT jobs of its realisations (job_for, one per seed), each probe the
// jobs of its realisations, all run as one batch. On the service's pool (orch::PoolRunner) the job
// cache answers finished jobs at once, which is what lets a restarted campaign replay its history.
#pragma once

#include "orchestrator/calibration/evaluator.hpp"
#include "orchestrator/job_runner.hpp"

namespace rockcal::calibration {

class RunnerEvaluator : public Evaluator {
 public:
  RunnerEvaluator(orch::JobRunner& runner, nlohmann::json job_template);

  // Throw EvaluationCancelled when the runner is cancelled (the campaign, or the server stops).
  std::vector<EvaluationOutcome> evaluate_batch(
      std::span<const EvaluationRequest> requests) override;
  std::vector<orch::Ensemble> probe_batch(std::span<const ProbeRequest> probes) override;
  void patch_template(const nlohmann::json& patch) override;
  // The job template later runs start from (the campaign's, with every patch merged in).
  const nlohmann::json& job_template() const { return job_template_; }

 private:
  // One ensemble per group of jobs (a run without a peak is a failed realisation, left out of the
  // statistics like any other failure, never taken as a load).
  std::vector<orch::Ensemble> run(const std::vector<std::vector<nlohmann::json>>& groups);

  orch::JobRunner& runner_;
  nlohmann::json job_template_;
};

}  // namespace rockcal::calibration
