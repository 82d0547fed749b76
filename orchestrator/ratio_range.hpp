// The UCT/BTT ratios a model reached over a set of runs, against the target's: the first fact of
// the sim-to-real gap when the target lies outside (the seed paper's model gave 10 where its lab
// gave 6, and no pair of strengths could change that). Calibration reports it over its
// evaluations, the diagnosis over its base grid.
#pragma once

#include <algorithm>
#include <limits>

namespace rockcal::orch {

struct RatioRange {
  double target = 0.0;  // the lab's UCT/BTT ratio
  double min = std::numeric_limits<double>::infinity();
  double max = -std::numeric_limits<double>::infinity();
  int runs = 0;  // model runs (or evaluations) the range spans

  void add(double ratio) {
    min = std::min(min, ratio);
    max = std::max(max, ratio);
    ++runs;
  }
  bool target_inside() const { return runs > 0 && target >= min && target <= max; }
};

}  // namespace rockcal::orch
