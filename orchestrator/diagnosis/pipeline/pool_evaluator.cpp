#include "orchestrator/diagnosis/pipeline/pool_evaluator.hpp"

#include <utility>

#include "orchestrator/job_batch.hpp"

namespace rockcal::diagnosis {
namespace {

using nlohmann::json;

// A finished job's result.json, or why there is none.
struct JobResult {
  json result;
  std::string error;
};

JobResult job_result(const orch::JobOutcome& outcome) {
  if (outcome.state != "succeeded" || !outcome.result) {
    return {nullptr,
            outcome.error.value_or("job " + std::to_string(outcome.job_id) + " " + outcome.state)};
  }
  return {json::parse(outcome.result->result, nullptr, false), ""};
}

}  // namespace

PoolEvaluator::PoolEvaluator(orch::JobService& service, std::int64_t campaign_id, json job_template,
                             std::vector<Target> targets, std::stop_token stop)
    : service_(service),
      campaign_id_(campaign_id),
      job_template_(std::move(job_template)),
      targets_(std::move(targets)),
      plan_(plan_runs(targets_)),
      stop_(stop) {
  json probe = job_template_;
  probe["bond"] = {{"fr0", 64.0}, {"fs0", 64.0}};
  model_ = parse_job_template(probe, TestKind::uct);
}

std::vector<RunOutcome> PoolEvaluator::run_batch(std::span<const RunRequest> requests) {
  // Every run of every request in one batch of the campaign (equal runs within it, a confirmation
  // at a grid node, are submitted once); a run the engine refuses is not submitted, its reason
  // kept as the run's error.
  std::vector<json> jobs;
  std::vector<std::vector<JobResult>> results(requests.size());
  std::vector<std::pair<std::size_t, std::size_t>> submitted;  // (request, run) of each job
  for (std::size_t r = 0; r < requests.size(); ++r) {
    for (const RunConditions& run : plan_.runs) {
      results[r].emplace_back();
      try {
        jobs.push_back(job_for(job_template_, model_, run, requests[r]));
        submitted.emplace_back(r, results[r].size() - 1);
      } catch (const std::exception& e) {
        results[r].back() = {nullptr, e.what()};
      }
    }
  }
  const auto finished = orch::run_batch(service_, campaign_id_, jobs, stop_);
  if (!finished) throw DiagnosisCancelled();
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    results[submitted[j].first][submitted[j].second] = job_result((*finished)[j]);
  }
  std::vector<RunOutcome> outcomes;
  for (std::size_t r = 0; r < requests.size(); ++r) {
    RunOutcome o;
    for (std::size_t i = 0; i < targets_.size(); ++i) {
      const JobResult& jr = results[r][plan_.run_of[i]];
      // A run without a peak comes back as a failed job ("no peak: ..."), like any failure.
      o.values.push_back(observable_value(jr.result, targets_[i].observable));
      if (!o.values.back() && o.error.empty()) {
        o.error = jr.error.empty() ? targets_[i].id + ": the run reported no " +
                                         to_string(targets_[i].observable)
                                   : jr.error;
      }
    }
    outcomes.push_back(std::move(o));
  }
  return outcomes;
}

}  // namespace rockcal::diagnosis
