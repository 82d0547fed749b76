#include "orchestrator/calibration/pool_evaluator.hpp"

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
  // Every realisation of both tests of every request, submitted before any is waited for.
  constexpr TestKind kTests[] = {TestKind::uct, TestKind::btt};
  std::vector<std::vector<Submitted>> jobs;  // [2 * request + test]
  for (const EvaluationRequest& r : requests) {
    for (TestKind test : kTests) {
      jobs.emplace_back();
      for (std::uint64_t seed : orch::realisation_seeds(r.sample_seed, r.realisations)) {
        jobs.back().push_back(
            {service_.submit_job(campaign_id_, job_for(job_template_, r, test, seed)), seed});
      }
    }
  }
  std::vector<orch::Ensemble> ensembles = collect(jobs);
  std::vector<EvaluationOutcome> outcomes;
  for (std::size_t i = 0; i < requests.size(); ++i) {
    outcomes.push_back(outcome_of(std::move(ensembles[2 * i]), std::move(ensembles[2 * i + 1])));
  }
  return outcomes;
}

std::vector<orch::Ensemble> PoolEvaluator::probe_batch(std::span<const ProbeRequest> probes) {
  std::vector<std::vector<Submitted>> jobs;
  for (const ProbeRequest& p : probes) {
    jobs.emplace_back();
    for (std::uint64_t seed : orch::realisation_seeds(p.sample_seed, p.realisations)) {
      jobs.back().push_back(
          {service_.submit_job(campaign_id_, job_for(job_template_, p, seed)), seed});
    }
  }
  return collect(jobs);
}

// A job whose run ended without a peak is a failed job ("no peak: ..."): it is left out of the
// ensemble's statistics like any other failure, never taken as a load.
std::vector<orch::Ensemble> PoolEvaluator::collect(
    const std::vector<std::vector<Submitted>>& groups) {
  std::vector<orch::Ensemble> ensembles;
  for (const std::vector<Submitted>& group : groups) {
    std::vector<orch::Realisation> realisations;
    for (const Submitted& s : group) {
      const orch::JobOutcome outcome = service_.wait_job(s.job_id, stop_);
      if (stop_.stop_requested() || outcome.state == "cancelled") throw EvaluationCancelled();
      realisations.push_back(orch::realisation(outcome, s.seed));
    }
    ensembles.push_back(orch::make_ensemble(std::move(realisations)));
  }
  return ensembles;
}

}  // namespace rockcal::calibration
