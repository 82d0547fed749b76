// From runs to an emulator's data: the realisations (packings) of one observable at each point,
// their pooled scatter, and each point's mean with the variance of that mean.
//
// Why: the packings' scatter is the noise the emulator must not chase. A point with several
// realisations measures it; a point with one does not, so each point's scatter is its own sample
// variance shrunk toward the pooled one (a scaled-inverse-chi-square prior with `prior_dof`
// degrees of freedom), and its mean's noise is that over the number of realisations.
#pragma once

#include <vector>

#include "orchestrator/inference/emulator/gp.hpp"

namespace rockcal::inference {

struct PointRuns {
  Eigen::VectorXd x;           // in [0, 1]^d
  std::vector<double> values;  // one per realisation that produced the observable
};

// The variance of one run about its point's mean, pooled over the points with replicates.
struct PooledScatter {
  double per_run_var = 0.0;
  int dof = 0;  // sum over points of (realisations - 1); 0: nothing measured it
};

PooledScatter pooled_scatter(const std::vector<PointRuns>& points);

// One row per point with at least one value. Without a measured scatter (dof 0) the noise
// variances are 0 and the emulator's nugget carries the scatter.
GpData gp_data(const std::vector<PointRuns>& points, const PooledScatter& scatter,
               double prior_dof = 4.0);

// The variance of one more run at any point: the pooled scatter when measured, else the nugget.
double per_run_noise(const PooledScatter& scatter, const Gp& gp);

}  // namespace rockcal::inference
