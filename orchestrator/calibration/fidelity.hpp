// Multi-fidelity: search on a coarse specimen, correct on the fine one. A search needs tens of
// evaluations; at the lab's resolution (D/R near 49) each costs minutes. But a change of resolution
// moves both peak loads by roughly common factors (measured, not assumed:
// docs/calibration-measurements.md), so the coarse model's local response in log space is a first
// Jacobian for the fine one. Each correction runs the fine tests at the current point (the
// campaign's realisations), and takes a Newton step ln x += J^-1 (ln target - ln fine loads) with J
// fitted to the coarse evaluations near the best point (least squares; the homogeneous scale step
// when they do not span two directions). The fine model's sensitivities need not be the coarse
// one's (docs/calibration-measurements.md: the seed lab case's fine steps swung about the answer by
// more than the fine specimen's cut scatter), so after every fine step J takes the secant the two
// latest fine evaluations measured (Broyden's update): the fine runs correct the Jacobian they are
// stepped with.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "orchestrator/calibration/ledger.hpp"

namespace rockcal::calibration {

struct FidelityStep {
  BondPoint point;  // the fine specimen's strengths (the search's x fine_strength_scale)
  std::optional<PeakLoads> fine;  // absent when a fine run failed
  PeakLoads rel_se{0.0, 0.0};
  std::string error;
  bool within_tolerance = false;
};

struct FidelityResult {
  std::vector<FidelityStep> steps;
  std::optional<PeakLoads> factors;  // fine / coarse loads at the coarse best point
  bool met = false;                  // the last step meets the targets at the fine resolution
  std::string jacobian;              // "fitted" (from n coarse points) or "scale only"
  int secant_updates = 0;            // Broyden updates of the fitted Jacobian from fine steps
};

// Up to `campaign.fine_corrections` fine evaluations from the coarse best point. Nothing when the
// campaign has no fine specimen. Throws EvaluationCancelled like the evaluator.
std::optional<FidelityResult> correct_on_fine(const std::vector<EvaluationRecord>& coarse,
                                              const EvaluationRecord& best,
                                              const CalibrationCampaign& campaign, double degree,
                                              Evaluator& evaluator);

nlohmann::json to_json(const FidelityResult& result, const CalibrationCampaign& campaign);

}  // namespace rockcal::calibration
