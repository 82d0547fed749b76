#include "orchestrator/diagnosis/pool_evaluator.hpp"

#include <map>

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
  // One job per distinct spec: equal runs within a batch (a confirmation at a grid node) are
  // submitted once.
  std::map<std::string, std::int64_t> job_of_spec;
  std::vector<std::vector<std::string>> spec_of(requests.size());
  std::map<std::string, std::string> refused;  // spec key -> why the engine refused it
  for (std::size_t r = 0; r < requests.size(); ++r) {
    for (const RunConditions& run : plan_.runs) {
      std::string key;
      try {
        key = job_for(job_template_, model_, run, requests[r]).dump();
      } catch (const std::exception& e) {
        key = "refused:" + std::to_string(r) + ":" + std::to_string(spec_of[r].size());
        refused[key] = e.what();
      }
      if (!refused.count(key) && !job_of_spec.count(key)) {
        job_of_spec[key] = service_.submit_job(campaign_id_, json::parse(key));
      }
      spec_of[r].push_back(key);
    }
  }
  std::map<std::string, JobResult> results;
  for (const auto& [key, id] : job_of_spec) {
    const orch::JobOutcome outcome = service_.wait_job(id, stop_);
    if (stop_.stop_requested() || outcome.state == "cancelled") throw DiagnosisCancelled();
    results[key] = job_result(outcome);
  }
  for (const auto& [key, why] : refused) results[key] = {nullptr, why};
  std::vector<RunOutcome> outcomes;
  for (std::size_t r = 0; r < requests.size(); ++r) {
    RunOutcome o;
    for (std::size_t i = 0; i < targets_.size(); ++i) {
      const JobResult& jr = results.at(spec_of[r][plan_.run_of[i]]);
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
