#include "orchestrator/calibration/pool_evaluator.hpp"

#include "orchestrator/job_batch.hpp"
#include "orchestrator/realisations.hpp"

namespace rockcal::calibration {

PoolEvaluator::PoolEvaluator(orch::JobService& service, std::int64_t campaign_id,
                             nlohmann::json job_template, std::stop_token stop)
    : service_(service),
      campaign_id_(campaign_id),
      job_template_(std::move(job_template)),
      stop_(stop) {}

std::vector<EvaluationOutcome> PoolEvaluator::evaluate_batch(
    std::span<const EvaluationRequest> requests) {
  // Every realisation of both tests of every request, in one batch.
  constexpr TestKind kTests[] = {TestKind::uct, TestKind::btt};
  Groups groups;  // [2 * request + test]
  for (const EvaluationRequest& r : requests) {
    for (TestKind test : kTests) {
      groups.emplace_back();
      for (std::uint64_t seed : orch::realisation_seeds(r.sample_seed, r.realisations)) {
        groups.back().push_back({job_for(job_template_, r, test, seed), seed});
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

std::vector<orch::Ensemble> PoolEvaluator::probe_batch(std::span<const ProbeRequest> probes) {
  Groups groups;
  for (const ProbeRequest& p : probes) {
    groups.emplace_back();
    for (std::uint64_t seed : orch::realisation_seeds(p.sample_seed, p.realisations)) {
      groups.back().push_back({job_for(job_template_, p, seed), seed});
    }
  }
  return run(groups);
}

void PoolEvaluator::patch_template(const nlohmann::json& patch) {
  job_template_.merge_patch(patch);
}

// A job whose run ended without a peak is a failed job ("no peak: ..."): it is left out of the
// ensemble's statistics like any other failure, never taken as a load.
std::vector<orch::Ensemble> PoolEvaluator::run(const Groups& groups) {
  std::vector<nlohmann::json> jobs;
  for (const auto& group : groups) {
    for (const Job& job : group) jobs.push_back(job.spec);
  }
  const auto outcomes = orch::run_batch(service_, campaign_id_, jobs, stop_);
  if (!outcomes) throw EvaluationCancelled();
  std::vector<orch::Ensemble> ensembles;
  std::size_t next = 0;
  for (const auto& group : groups) {
    std::vector<orch::Realisation> realisations;
    for (const Job& job : group)
      realisations.push_back(orch::realisation((*outcomes)[next++], job.seed));
    ensembles.push_back(orch::make_ensemble(std::move(realisations)));
  }
  return ensembles;
}

}  // namespace rockcal::calibration
