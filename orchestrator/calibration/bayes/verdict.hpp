// The verdict of a "bayes" calibration, from its posterior's own fields: feasible when the
// predicted loads at the estimate meet both targets within the tolerance; otherwise the cause
// that the fields show (a bound the region presses on, a ratio the runs never reached, the
// emulators' variance when the budget ran out, a cancellation, no run at all).
#pragma once

#include "orchestrator/calibration/report.hpp"

namespace rockcal::calibration {

void judge_posterior(CalibrationReport& report, const CalibrationCampaign& campaign);

}  // namespace rockcal::calibration
