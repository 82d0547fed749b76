// Can the data see an effect at all? Adding a parameter always improves a fit, so an effect must
// first show that it moves something the bond strengths cannot: with (F_r0, F_s0) re-fitted to the
// calibration targets at each s, some observation must move by more than its budget + lab
// uncertainty as s walks over [0, 1]. An effect that only rescales every strength (the strengths
// absorb it) fails this, however well it fits.
#pragma once

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

}  // namespace rockcal::diagnosis
