// The service's worker pool as the calibration's Evaluator: each request of a batch becomes the UCT
// and BTT jobs of its realisations, run as one batch of the campaign (orch::run_batch). The job
// cache answers finished jobs at once, which is what lets a restarted campaign replay its history.
#pragma once

#include <cstdint>
#include <stop_token>

#include "orchestrator/calibration/evaluator.hpp"
#include "orchestrator/job_service.hpp"

namespace rockcal::calibration {

class PoolEvaluator : public Evaluator {
 public:
  PoolEvaluator(orch::JobService& service, std::int64_t campaign_id, nlohmann::json job_template,
                std::stop_token stop);

  // Throws EvaluationCancelled when the campaign is cancelled or the server stops.
  std::vector<EvaluationOutcome> evaluate_batch(
      std::span<const EvaluationRequest> requests) override;
  std::vector<orch::Ensemble> probe_batch(std::span<const ProbeRequest> probes) override;
  void patch_template(const nlohmann::json& patch) override;

 private:
  struct Job {
    nlohmann::json spec;
    std::uint64_t seed;
  };
  using Groups = std::vector<std::vector<Job>>;  // one group per ensemble
  // Runs every group's jobs in one batch and makes each group an ensemble.
  std::vector<orch::Ensemble> run(const Groups& groups);

  orch::JobService& service_;
  std::int64_t campaign_id_;
  nlohmann::json job_template_;
  std::stop_token stop_;
};

}  // namespace rockcal::calibration
