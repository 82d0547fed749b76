// Can the data see an effect at all? Adding a parameter always improves a fit, so an effect must
// first show that it moves something the bond strengths cannot: with (F_r0, F_s0) re-fitted to the
// calibration targets at each s, some observation must move by more than its budget + lab
// uncertainty as s walks over [0, 1]. An effect that only rescales every strength (the strengths
// absorb it) fails this, however well it fits.
// And the observation it moves must include a calibration one: the effect's parameter is fitted
// on the calibration observations, so one that moves only held-out observations is fitted on
// data that cannot see it. Its fitted value is then wherever the optimiser stopped (a bound, a
// start), and the held-out gap it closes there is a choice, not a prediction.
#pragma once

#include <string>
#include <vector>

#include "orchestrator/diagnosis/analysis/candidate_result.hpp"
#include "orchestrator/diagnosis/analysis/observations.hpp"
#include "orchestrator/diagnosis/analysis/surface_fit.hpp"

namespace rockcal::diagnosis {

// `steps` values of u from 0 to 1, each with the strengths re-fitted on the surfaces, compared
// with u = 0, or with `base` (the base model's fitted ln values) for an effect whose u = 0 is not
// the base model (one that jumps at neutral).
Identifiability identifiability(const SurfaceSet& surfaces, const Objective& objective,
                                const std::vector<Target>& targets,
                                const std::vector<double>& budget, int steps = 11,
                                const std::vector<double>* base = nullptr);

// Why an effect is or is not identifiable, in a sentence naming the observations it moves.
std::string identifiability_reason(const Identifiability& id, const std::vector<Target>& targets);

}  // namespace rockcal::diagnosis
