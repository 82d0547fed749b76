// From runs to an emulator's data: the runs (packings) of one observable at each point become one
// row, their mean, with how many there were.
//
// Why: the packings' scatter is the noise the emulator must not chase. It is one run's variance
// at the point (the emulator's nugget and its trend over the box, learned from every residual at
// once, which a handful of replicates alone would pin poorly), and a point's mean of m runs
// carries it over m: a point run on several packings is known better, the same rule that lets the
// design value a further realisation. The runs' spread about each mean is kept too (within_ss),
// for an emulator whose few points cannot tell misfit from scatter (GpOptions::replicate_spread).
#pragma once

#include <vector>

#include "orchestrator/inference/emulator/gp.hpp"

namespace rockcal::inference {

struct PointRuns {
  Eigen::VectorXd x;           // in [0, 1]^d
  std::vector<double> values;  // one per run that produced the observable
};

// One row per point with at least one value.
GpData gp_data(const std::vector<PointRuns>& points);

}  // namespace rockcal::inference
