// The diagnosis driver (docs/diagnosis.md, "Design"): the base model's grid, the numerical budget
// and the screen at its first fit, the kept effects' response surfaces, a calibration per
// candidate, identifiability, confirmation by real runs, gap closure G, the verdict and its
// confidence, and the next test. Engine runs go through the Evaluator in batches (base grid, budget
// and screen, effects' surfaces, confirmations), each submitted whole so the pool runs it in
// parallel; everything else works on the surfaces and takes seconds.
//
// Deterministic: for a campaign and the evaluator's answers the requested runs are fixed, so a
// restarted diagnosis replays its finished runs from the job cache.
#pragma once

#include <functional>
#include <stop_token>

#include <nlohmann/json.hpp>

#include "orchestrator/diagnosis/analysis/evaluator.hpp"
#include "orchestrator/diagnosis/pipeline/campaign.hpp"
#include "orchestrator/diagnosis/pipeline/result.hpp"

namespace rockcal::diagnosis {

struct DiagnosisOptions {
  std::stop_token stop;  // checked before every batch
  // Called as each phase starts: {"phase": "grid" | "budget" | "surfaces" | "confirm" |
  // "analysis" | "next_test", "step": k, "steps": 6 (5 without the next test), "runs": model
  // points in this phase}.
  std::function<void(const nlohmann::json& progress)> on_progress;
};

// Runs the whole diagnosis in the calling thread. Throws DiagnosisCancelled when stopped, and
// std::runtime_error when the base model cannot be fitted at all (every grid run failed).
DiagnosisResult run_diagnosis(const DiagnosisCampaign& campaign, Evaluator& evaluator,
                              const DiagnosisOptions& options = {});

}  // namespace rockcal::diagnosis
