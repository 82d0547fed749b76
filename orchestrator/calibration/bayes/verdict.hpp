// The verdict of a "bayes" calibration, from its posterior's own fields: feasible when the
// predicted loads at the estimate meet both targets (acceptance below); otherwise the cause
// that the fields show (a bound the region presses on, a ratio the runs never reached, the
// emulators' variance when the budget ran out, a cancellation, no run at all).
#pragma once

#include "orchestrator/calibration/report.hpp"

namespace rockcal::calibration {

// The relative error each load may keep and still count as met: the tolerance, or the lab's
// stated uncertainty of that mean (inference.lab_uncertainty, when the request gives it) where
// that is wider. A lab UCS stated as 266 +- 98 MPa is met by a model anywhere within it; the
// search still aims at the lab's means, and the verdict says which of the two was met.
struct Acceptance {
  double uct = 0.0;
  double btt = 0.0;
  bool widened = false;  // the lab's uncertainty is wider than the tolerance for a load
};
Acceptance acceptance(const CalibrationCampaign& campaign);

void judge_posterior(CalibrationReport& report, const CalibrationCampaign& campaign);

}  // namespace rockcal::calibration
