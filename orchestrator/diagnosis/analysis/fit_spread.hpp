// The fit's own uncertainty, carried into its predictions. A candidate's strengths (and its
// parameter) are fitted to calibration observations that carry numerical noise and lab
// uncertainty, so the fitted point is one of the points the data allow: along a direction the
// calibration observations constrain weakly it may lie far from the truth, and a held-out
// observation that depends on that direction is then predicted with a spread no budget shows (a
// null twin's squat UCT, held out, missing by twice its own noise while its fit's F_r0 lies 20%
// from the truth's: docs/diagnosis-measurements.md). Read as a Laplace approximation of the
// calibration's posterior on the surfaces: with g_i = d ln(target i) / dz at the fit,
//   Sigma = (sum over calibration targets of g_i g_i^T / (budget_i^2 + sigma_i^2) + 12 I)^-1,
// the 12 I being the unit box's uniform prior (variance 1/12 per axis), and a prediction's
// variance from the fit is g_i^T Sigma g_i.
#pragma once

#include <vector>

#include "orchestrator/diagnosis/analysis/observations.hpp"
#include "orchestrator/diagnosis/analysis/surface_fit.hpp"

namespace rockcal::diagnosis {

// Per target, g_i^T Sigma g_i at the unit-cube fit z (central differences on the surfaces,
// one-sided at a face of the cube); 0 where the target has no surface or z is empty.
std::vector<double> fit_spread(const SurfaceSet& surfaces, const std::vector<double>& z,
                               const std::vector<Target>& targets,
                               const std::vector<double>& budget);

}  // namespace rockcal::diagnosis
