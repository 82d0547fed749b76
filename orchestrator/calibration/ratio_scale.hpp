// Ratio-then-scale: when the model is homogeneous (see homogeneity.hpp), the UCT/BTT ratio depends
// on s = ln(F_s0/F_r0) only, so the 2-D search becomes a 1-D search for the ratio (NLopt on s) and
// a scale that follows in closed form: with both loads ~ c^p, the log-misfit is quadratic in ln c
// and its minimum is p ln c = -(w_u e_u + w_b e_b) / (w_u + w_b), e = ln(sim/target). Every 1-D
// evaluation is already placed at the scale predicted from the nearest evaluated ratio, so when the
// ratio is found the loads usually are too.
#pragma once

#include "orchestrator/calibration/homogeneity.hpp"
#include "orchestrator/calibration/ledger.hpp"

namespace rockcal::calibration {

// Runs the 1-D ratio search and up to three closed-form scale steps. Each scale step is also a
// homogeneity check (a pair on one ratio line), appended to `checks`; a failed one ends the steps.
// Returns normally when done without meeting the targets; throws SearchDone / EvaluationCancelled
// like the ledger.
void ratio_then_scale(Ledger& ledger, const CalibrationCampaign& campaign, double degree,
                      HomogeneityChecks& checks);

}  // namespace rockcal::calibration
