// What a diagnosis found, as the pipeline hands it on: the budget, every candidate's fits, the
// verdict and its confidence. The report (report/) renders it; the campaign kind stores it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "orchestrator/diagnosis/analysis/budget.hpp"
#include "orchestrator/diagnosis/analysis/candidate_result.hpp"
#include "orchestrator/diagnosis/analysis/consistency.hpp"
#include "orchestrator/diagnosis/analysis/evaluator.hpp"
#include "orchestrator/diagnosis/analysis/next_test.hpp"
#include "orchestrator/diagnosis/analysis/ratio.hpp"
#include "orchestrator/diagnosis/analysis/screen.hpp"
#include "orchestrator/diagnosis/analysis/verdict.hpp"

namespace rockcal::diagnosis {

// The screening (screen.hpp): every effect at s = 1 at the base model's first fit, in the budget's
// batch there; effects that are not `visible` get no surfaces and are not candidates.
struct ScreenResult {
  bool enabled = false;
  ModelPoint point;       // the base model's first fit
  std::vector<double> z;  // the same in the unit square (ln F_r0, ln F_s0)
  // The second point (balanced_point, driver.cpp): equal strengths at the first's geometric mean,
  // each within its bounds;
  // empty z when it lies within a grid step of the first.
  ModelPoint balanced_point;
  std::vector<double> balanced_z;
  std::vector<ScreenedEffect> effects;  // request order
  int model_points = 0;                 // the effects' runs (the base's are the budget's)
  int skipped_model_points = 0;         // the surfaces' model points of the effects left out
};

struct DiagnosisResult {
  // The budget the residuals are judged against (gap test, calibration-fit rule after the
  // confirmations, seed checks, bootstrap), measured at the base model's confirmed fit (the model
  // whose residuals they are; on a demo twin the budget doubled between the two fits).
  Budget budget;
  ModelPoint budget_point;
  // The first budget, at the base model's fit on lab uncertainties alone: the calibrations'
  // weights. The same as `budget` when the confirmed fit kept the first fit's budget points.
  Budget weight_budget;
  ModelPoint weight_budget_point;
  double combined_calibration = 0.0;
  double combined_held_out = 0.0;
  // The base model's held-out residuals (real runs) in budgets: rms_in_budgets, what the verdict
  // calls a gap above the campaign's decision.gap_budgets.
  std::optional<double> held_out_budgets;
  // The named effect's share of that gap beyond noise (gap_closure_beyond_noise, its real runs);
  // nullopt when no effect is named or the base has no gap beyond noise.
  std::optional<double> gap_closure_beyond_noise;
  ScreenResult screen;
  // [0] = the base, then the effects the screen kept, in request order.
  std::vector<CandidateResult> candidates;
  std::optional<LabRatio> ratio;
  Verdict verdict;
  Confidence confidence;
  int model_points = 0;  // distinct model points run (each = one job per distinct condition)
  int failed_values = 0;
  std::string first_error;              // of the first run that left a value missing
  std::vector<int> base_grid_failures;  // per target: base grid runs without a value
  // Pairs of observations under nearly the same conditions that disagree beyond their
  // uncertainties: the data's own, named in the verdict and not charged to the model
  // (consistency.hpp).
  std::vector<Inconsistency> inconsistencies;
  // The lab test that would best tell the leading hypotheses apart, and the one that would make
  // each effect the calibration cannot identify visible (next_test_runs.hpp).
  NextTest next_test;
};

}  // namespace rockcal::diagnosis
