// From targets to engine jobs and back: which distinct runs a set of targets needs, the canonical
// job of one run, and the observable a finished run yields.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/spec.hpp"
#include "orchestrator/diagnosis/analysis/evaluator.hpp"
#include "orchestrator/diagnosis/analysis/observations.hpp"

namespace rockcal::diagnosis {

// Targets with equal conditions share a run: `runs` are the distinct conditions, `run_of[i]` the
// run that measures target i.
struct RunPlan {
  std::vector<RunConditions> runs;
  std::vector<std::size_t> run_of;
};
RunPlan plan_runs(const std::vector<Target>& targets);

// The canonical job (parse_job + to_json, so equal runs are byte-equal and the job cache knows
// them) for one run of `request`. `job_template` is the campaign's "job" block, `model` its parsed
// form (for the sample radius and K_r that a refined resolution scales). A refined resolution r
// keeps the continuum the same: R / r, K_r / r (E ~ K_r / R, eq. 3) and bond strengths / r^2 (a
// bond carries stress x R^2). An effect is named with its fitted parameter at effect_value_at(s).
// Throws SpecError for a job the engine refuses, std::invalid_argument for an unknown effect.
nlohmann::json job_for(const nlohmann::json& job_template, const JobSpec& model,
                       const RunConditions& conditions, const RunRequest& request);

// What a finished run's result.json says about one observable; nullopt when it has no value. A run
// that ended without a peak (orch::no_peak_reason) is a failed run with no value at all: the
// largest load it saw is not a peak, and the service stores it as a failed job.
std::optional<double> observable_value(const nlohmann::json& result, Observable observable);

}  // namespace rockcal::diagnosis
