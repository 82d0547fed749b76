#include "orchestrator/calibration/pool_evaluator.hpp"

namespace rockcal::calibration {
namespace {

// The peak load of a finished job, or why there is none.
struct JobLoad {
  std::optional<double> peak_load_n;
  std::string error;
};

JobLoad job_load(const orch::JobOutcome& outcome) {
  if (outcome.state != "succeeded" || !outcome.result || !outcome.result->peak_load) {
    return {std::nullopt,
            outcome.error.value_or("job " + std::to_string(outcome.job_id) + " " + outcome.state)};
  }
  // A run that hit max_strain before the load fell has no peak: its "peak" is only a lower bound.
  const nlohmann::json result = nlohmann::json::parse(outcome.result->result, nullptr, false);
  if (result.is_object() && !result.value("peak_reached", true)) {
    return {std::nullopt, "job " + std::to_string(outcome.job_id) +
                              ": peak not reached before loading.max_strain"};
  }
  return {outcome.result->peak_load, ""};
}

}  // namespace

PoolEvaluator::PoolEvaluator(orch::JobService& service, std::int64_t campaign_id,
                             nlohmann::json job_template, std::stop_token stop)
    : service_(service),
      campaign_id_(campaign_id),
      job_template_(std::move(job_template)),
      stop_(stop) {}

std::vector<EvaluationOutcome> PoolEvaluator::evaluate_batch(
    std::span<const EvaluationRequest> requests) {
  std::vector<std::int64_t> job_ids;
  for (const EvaluationRequest& r : requests) {
    for (TestKind test : {TestKind::uct, TestKind::btt}) {
      job_ids.push_back(service_.submit_job(campaign_id_, job_for(job_template_, r, test)));
    }
  }
  std::vector<JobLoad> loads;
  for (std::int64_t id : job_ids) {
    const orch::JobOutcome outcome = service_.wait_job(id, stop_);
    if (stop_.stop_requested() || outcome.state == "cancelled") throw EvaluationCancelled();
    loads.push_back(job_load(outcome));
  }
  std::vector<EvaluationOutcome> outcomes;
  for (std::size_t i = 0; i < requests.size(); ++i) {
    const JobLoad& uct = loads[2 * i];
    const JobLoad& btt = loads[2 * i + 1];
    if (uct.peak_load_n && btt.peak_load_n) {
      outcomes.push_back({PeakLoads{*uct.peak_load_n, *btt.peak_load_n}, ""});
    } else {
      outcomes.push_back({std::nullopt, uct.error.empty() ? btt.error : uct.error});
    }
  }
  return outcomes;
}

}  // namespace rockcal::calibration
