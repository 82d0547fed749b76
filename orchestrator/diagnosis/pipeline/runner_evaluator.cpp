#include "orchestrator/diagnosis/pipeline/runner_evaluator.hpp"

#include <utility>

namespace rockcal::diagnosis {

using nlohmann::json;

RunnerEvaluator::RunnerEvaluator(orch::JobRunner& runner, json job_template,
                                 std::vector<Target> targets)
    : runner_(runner), job_template_(std::move(job_template)), targets_(std::move(targets)) {
  json probe = job_template_;
  probe["bond"] = {{"fr0", 64.0}, {"fs0", 64.0}};
  model_ = parse_job_template(probe, TestKind::uct);
}

std::vector<RunOutcome> RunnerEvaluator::run_batch(std::span<const RunRequest> requests) {
  return run_on(requests, targets_);
}

std::vector<RunOutcome> RunnerEvaluator::run_on(std::span<const RunRequest> requests,
                                                const std::vector<Target>& targets) {
  const RunPlan plan = plan_runs(targets);
  // Every run of every request in one batch (equal runs within it, a confirmation at a grid node,
  // are run once); a run the engine refuses is not submitted, its reason kept as the run's error.
  std::vector<json> jobs;
  std::vector<std::vector<orch::Realisation>> runs(requests.size());
  std::vector<std::pair<std::size_t, std::size_t>> submitted;  // (request, run) of each job
  for (std::size_t r = 0; r < requests.size(); ++r) {
    for (const RunConditions& conditions : plan.runs) {
      runs[r].emplace_back();
      try {
        jobs.push_back(job_for(job_template_, model_, conditions, requests[r]));
        submitted.emplace_back(r, runs[r].size() - 1);
      } catch (const std::exception& e) {
        runs[r].back().error = e.what();
      }
    }
  }
  std::optional<std::vector<orch::Realisation>> finished = runner_.run(jobs);
  if (!finished) throw DiagnosisCancelled();
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    runs[submitted[j].first][submitted[j].second] = std::move((*finished)[j]);
  }
  std::vector<RunOutcome> outcomes;
  for (std::size_t r = 0; r < requests.size(); ++r) {
    RunOutcome o;
    for (std::size_t i = 0; i < targets.size(); ++i) {
      const orch::Realisation& run = runs[r][plan.run_of[i]];
      // A run without a peak comes back as a failed run ("no peak: ..."), like any failure.
      o.values.push_back(observable_value(run.result, targets[i].observable));
      if (!o.values.back() && o.error.empty()) {
        o.error = run.error.empty()
                      ? targets[i].id + ": the run reported no " + to_string(targets[i].observable)
                      : run.error;
      }
    }
    outcomes.push_back(std::move(o));
  }
  return outcomes;
}

}  // namespace rockcal::diagnosis
