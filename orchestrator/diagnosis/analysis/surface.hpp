// Response surfaces: ln(observable) as a function of the unit-cube coordinates z (ln F_r0 and
// ln F_s0 mapped to [0, 1] over the bounds, plus the effect's s for a candidate), built from the
// design's runs by the inference core's Gaussian-process emulator (inference/emulator/gp.hpp): a
// linear trend (the loads' homogeneity in the strengths), a Matern 5/2 departure from it and a
// nugget for the runs' scatter, hyperparameters by restricted likelihood. A global quadratic was
// too stiff for a box spanning a factor of 16 in each strength, and an interpolant passes through
// the scatter; the emulator follows a smooth response, averages the scatter by its likelihood and
// says how well the runs pin the surface at a point: its variance there, the emulator's share of
// the held-out evidence's predictive variance (evidence.hpp).
// The emulator works in the runs' own box (their bounding box mapped to [0, 1]^d), so its
// correlation lengths are in units of what the design spans: a local design's star a tenth of the
// box wide is resolved as a global grid over the whole box is.
#pragma once

#include <optional>
#include <span>
#include <vector>

// GCC 12 with -march=native (AVX-512) warns falsely about an uninitialised register inside
// Eigen's matrix-vector kernels (-Wmaybe-uninitialized in _mm512_extractf64x4_pd); the warning is
// in Eigen's code, not ours, so it is silenced for the Eigen headers only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Eigen/Dense>
#pragma GCC diagnostic pop

#include "orchestrator/inference/emulator/gp.hpp"

namespace rockcal::diagnosis {

struct Surface {
  int dims = 0;
  Eigen::VectorXd lo, span;  // the runs' box: the emulator's x = (z - lo) / span
  inference::Gp gp;
  // Leave-one-out rms (ln units): each run predicted by the emulator conditioned on the others
  // (at the fitted hyperparameters). The error to expect between the runs, their scatter included.
  double rms = 0.0;
  int points = 0;
};

// The fewest runs a surface is fitted to: what the emulator's linear trend needs to leave its
// departure anything, 2 (d + 1).
int minimum_surface_points(int dims);

// The surface through the points (z[k], y[k]); nullopt with fewer than minimum_surface_points or
// more than 8 coordinates, with an axis the points do not span (nothing says how the observable
// moves along it), or when the emulator cannot be fitted.
std::optional<Surface> fit_surface(const std::vector<std::vector<double>>& z,
                                   const std::vector<double>& y);

// The emulator's mean at z (no allocation: what the calibrations on the surfaces call).
double evaluate(const Surface& surface, std::span<const double> z);
// The emulator's variance at z: how far the mean may be from the noise-free response there.
double variance_at(const Surface& surface, std::span<const double> z);

}  // namespace rockcal::diagnosis
