#include "orchestrator/calibration/runner_evaluator.hpp"

#include "orchestrator/ensemble.hpp"

namespace rockcal::calibration {

RunnerEvaluator::RunnerEvaluator(orch::JobRunner& runner, nlohmann::json job_template)
    : runner_(runner), job_template_(std::move(job_template)) {}

std::vector<EvaluationOutcome> RunnerEvaluator::evaluate_batch(
    std::span<const EvaluationRequest> requests) {
  // Every realisation of both tests of every request, in one batch.
  std::vector<std::vector<nlohmann::json>> groups;  // [2 * request + test]
  for (const EvaluationRequest& r : requests) {
    for (TestKind test : {TestKind::uct, TestKind::btt}) {
      groups.emplace_back();
      for (std::uint64_t seed : orch::realisation_seeds(r.sample_seed, r.realisations)) {
        groups.back().push_back(job_for(job_template_, r, test, seed));
      }
    }
  }
  std::vector<orch::Ensemble> ensembles = run(groups);
  std::vector<EvaluationOutcome> outcomes;
  for (std::size_t i = 0; i < requests.size(); ++i) {
    outcomes.push_back(outcome_of(std::move(ensembles[2 * i]), std::move(ensembles[2 * i + 1])));
  }
  return outcomes;
}

std::vector<orch::Ensemble> RunnerEvaluator::probe_batch(std::span<const ProbeRequest> probes) {
  std::vector<std::vector<nlohmann::json>> groups;
  for (const ProbeRequest& p : probes) {
    groups.emplace_back();
    for (std::uint64_t seed : orch::realisation_seeds(p.sample_seed, p.realisations)) {
      groups.back().push_back(job_for(job_template_, p, seed));
    }
  }
  return run(groups);
}

void RunnerEvaluator::patch_template(const nlohmann::json& patch) {
  job_template_.merge_patch(patch);
}

std::vector<orch::Ensemble> RunnerEvaluator::run(
    const std::vector<std::vector<nlohmann::json>>& groups) {
  std::optional<std::vector<orch::Ensemble>> ensembles = orch::run_ensembles(runner_, groups);
  if (!ensembles) throw EvaluationCancelled();
  return std::move(*ensembles);
}

}  // namespace rockcal::calibration
