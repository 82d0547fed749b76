// Whether the check runs at the estimate agree with what the posterior predicted there. The
// emulators predict the mean ln load at the estimate with variance emulator_sd^2; a mean over n
// packings scatters about it by run_sd^2 / n more. A check mean outside the 99% interval of that
// sum means the emulators are wrong at the estimate, and "feasible" would rest on them alone.
#pragma once

#include <optional>

#include "orchestrator/calibration/bayes/summary.hpp"
#include "orchestrator/ensemble.hpp"

namespace rockcal::calibration {

inline constexpr double kCheckLevel = 0.99;

// Of the ensemble's successful runs: their geometric mean against the prediction, and the sd of
// ln(that mean) the prediction allows. Empty without a successful run.
std::optional<CheckAgreement> check_agreement(const PredictedLoad& predicted,
                                              const orch::Ensemble& check);

}  // namespace rockcal::calibration
