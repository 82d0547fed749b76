// Where the model gives a result at all: the chance that a run at x ends with the observable.
//
// Why: a calibration target is a peak load, and some strengths give none (a specimen that is
// still loading up when the bonds can no longer set its peak). A failed run has no value for the
// emulators, which then extrapolate over the failing region as if it were unexplored: the
// posterior puts mass there and the design keeps sending runs into it. The lab's rock did reach a
// peak, so a region where runs fail is not a candidate answer. The chance of a result is estimated
// by kernel smoothing of the runs' outcomes (1 with a result, 0 without), the weights taken
// relative to the nearest run so that unexplored space takes its nearest runs' outcome (failures
// come in regions bounded by a strength ratio, not at points), plus a small prior weight a on
// "feasible": p(x) = (sum_i w_i y_i + a) / (sum_i w_i + a), w_i = exp(-(d_i^2 - d_min^2) / 2 l^2).
// Its log adds to the posterior's (PosteriorGrid::log_feasibility).
#pragma once

#include <Eigen/Dense>

#include "orchestrator/inference/posterior/posterior.hpp"

namespace rockcal::inference {

struct RunResults {
  Eigen::MatrixXd x;          // n x d: where runs were made (the unit box)
  Eigen::VectorXd has_value;  // n: 1 where the run gave the observable, 0 where it could not
};

struct FeasibilitySettings {
  double length = 0.05;        // the kernel's length on the unit box (under `metric` when set)
  double prior_weight = 0.05;  // a, against the nearest run's weight 1
  // d x d: the squared distance between runs is dx' M dx (empty: the identity). Where what decides
  // a result is one combination of the parameters (a strength ratio), M measures mostly along it,
  // and an outcome holds far along the directions that leave it unchanged.
  Eigen::MatrixXd metric;
};

// The squared distance from x to each row of `at` under s.metric.
Eigen::VectorXd squared_distances(const Eigen::MatrixXd& at, const Eigen::VectorXd& x,
                                  const FeasibilitySettings& s);

// p(x) in (0, 1]; 1 with no runs.
double feasibility(const RunResults& runs, const Eigen::VectorXd& x,
                   const FeasibilitySettings& s = {});

// Two resolutions' outcomes as one: `over`'s runs (the resolution the posterior answers for) and
// those of `under` (another resolution, whose zones without a result the first one shares only in
// part) that lie farther than `reach` from every run of `over`. Near its own runs the answered
// resolution's outcomes replace the other's; elsewhere the other's are all there is.
RunResults overlaid(const RunResults& under, const RunResults& over, double reach,
                    const FeasibilitySettings& s = {});

// Sets grid.log_feasibility from the runs and re-weighs the grid (an empty `runs` clears it).
void apply_feasibility(PosteriorGrid& grid, const RunResults& runs,
                       const std::vector<Target>& targets, const FeasibilitySettings& s = {});

}  // namespace rockcal::inference
