// The "twin" campaign kind: a synthetic twin made on the service's pool. Its runs go through the
// one job runner every campaign uses (orchestrator/job_runner.hpp), so they are cached like any
// job, a twin re-made after a crash or with a new noise seed replays the runs it has, and a
// diagnosis in the same store finds the twin's runs too.
//
// Request: {"kind": "twin", "name"?, "effect", "value" (unless "none"), "seed"?, "noise"?,
//           "resolution"?, "job"? (the template; default demo_twin_template())}
// Summary: {"kind": "twin", "progress": {...}, "dataset": {...}, "truth": {...}, "design": {...}}
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "orchestrator/campaign_kinds.hpp"
#include "orchestrator/diagnosis/twin/twin.hpp"
#include "orchestrator/diagnosis/twin/twin_design.hpp"
#include "orchestrator/job_runner.hpp"
#include "orchestrator/progress_model.hpp"

namespace rockcal::diagnosis {

struct TwinCampaign {
  std::string name;
  TwinRequest twin;
  nlohmann::json job_template;
};

// Throws orch::RequestError naming the field ("effect", "value", "noise", "job.sample.radius").
TwinCampaign parse_twin_campaign(const nlohmann::json& request);

struct TwinCancelled : std::runtime_error {
  TwinCancelled() : std::runtime_error("twin cancelled") {}
};

// Runs jobs as one batch on `runner` (the campaign's pool, orch::PoolRunner) and returns each
// run's result.json, in order. Throws std::runtime_error with the job's id, state and failure
// reason for a failed run (a run without a peak fails), TwinCancelled when the runner is
// cancelled (the campaign, or the server stops).
RunJobs results_of(orch::JobRunner& runner);

// The jobs a twin plans, by part: "design" (its template's base UCT) and "observations" (the
// distinct runs of its observations, twin_jobs): the budget of its progress model
// (orchestrator/progress_model.hpp, unit "jobs").
std::vector<orch::BudgetPart> planned_twin_job_parts(const TwinCampaign& c);

orch::CampaignKind twin_kind();

}  // namespace rockcal::diagnosis
