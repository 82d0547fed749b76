// When the credible region is too wide to call the strengths unique: the test from the engine's
// menu whose lab value would shrink it most, with the expected shrinkage and the runs behind it.
//
// Why: two loads known to a few per cent often leave a long, thin region (the strengths trade off
// along it); a third observable that changes along the region's long axis cuts it. Its worth is a
// linearised Bayesian update: with the region's variance lambda along its long axis (unit log
// box), a test whose ln value changes by d per unit along that axis and is measured to sd s
// leaves lambda s^2 / (lambda d^2 + s^2), so the axis shrinks by sqrt(s^2 / (lambda d^2 + s^2)).
// d comes from the emulator for the UCT's modulus (every run measured it) and from runs at the
// axis's two ends for the triaxial peak at 0.1 x the target UCS, a disc 1.5 x wider and a squat
// (H/D = 1) UCT. A difference within two standard errors of the runs' scatter counts as none.
#pragma once

#include <optional>

#include "orchestrator/calibration/bayes/emulators.hpp"
#include "orchestrator/calibration/suggestion.hpp"

namespace rockcal::calibration {

// Candidates' expected shrinkage (1 - new axis / old axis) in Suggestion::candidates; the best as
// the suggestion. Throws EvaluationCancelled like the evaluator.
std::optional<Suggestion> next_test(const Emulators& m,
                                    const std::vector<EvaluationRecord>& history,
                                    const CalibrationCampaign& c, Evaluator& evaluator,
                                    int packings);

}  // namespace rockcal::calibration
