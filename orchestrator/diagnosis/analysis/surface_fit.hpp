// Calibration of one candidate on its response surfaces: NLopt minimises the weighted sum of
// squared ln(sim/lab) residuals over the calibration targets, where sim is the surface. A surface
// costs microseconds, so the search can afford several starts and bootstrap replicates can afford
// a calibration each.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "orchestrator/diagnosis/analysis/surface.hpp"

namespace rockcal::diagnosis {

// One candidate's surfaces, one per target (nullopt where too few runs succeeded to fit one).
struct SurfaceSet {
  int dims = 0;
  std::vector<std::optional<Surface>> per_target;
};

// ln(sim) of every target at z; NaN where the target has no surface.
std::vector<double> predict(const SurfaceSet& surfaces, std::span<const double> z);

// d ln(target) / dz of every target at z ([target][axis]): central differences of step 0.02 on
// the surfaces, one-sided at a face of the cube; NaN where a target has no surface.
std::vector<std::vector<double>> surface_gradients(const SurfaceSet& surfaces,
                                                   std::span<const double> z);

struct Objective {
  std::vector<double> ln_lab;
  std::vector<double> weight;  // per target; 0 = not in the objective (held out, no surface)
};

double misfit(const Objective& objective, const std::vector<double>& ln_sim);

struct SurfaceCalibration {
  std::vector<double> z;  // unit-cube point (dims of the surfaces)
  double misfit = 0.0;
  std::vector<double> history;  // best misfit so far after each evaluation of the winning start
  int evaluations = 0;          // over all starts
};

// BOBYQA on [0, 1]^d from each start (the best end wins; ties keep the earlier start, so the
// result is deterministic). With `fixed_s` the last coordinate is held there and only the bond
// strengths move (the identifiability check).
SurfaceCalibration calibrate_on_surfaces(const SurfaceSet& surfaces, const Objective& objective,
                                         const std::vector<std::vector<double>>& starts,
                                         std::optional<double> fixed_s = std::nullopt);

// A re-fit near a known point `z`: from z and the 2^d lattice starts, on the surfaces shifted by
// `offset` per target (real - surface at a run; empty = no shift). Fitting surface + offset to the
// lab values is fitting the surface to lab - offset.
SurfaceCalibration refit_near(const SurfaceSet& surfaces, Objective objective,
                              const std::vector<double>& z, const std::vector<double>& offset);

// The interior points {1/(2k), 3/(2k), ...}^d: k per axis, away from the bounds where BOBYQA's
// first trust region would be clipped.
std::vector<std::vector<double>> lattice_starts(int dims, int per_axis);

}  // namespace rockcal::diagnosis
