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
  // Set by a search with emulators: the ratios their means give at the points run. One run's ratio
  // carries its packing's scatter (a disc's ln load scatters 0.2-0.3), so the runs' extremes
  // overstate the reach; when set, reach is judged on these.
  double emulated_lo = 0.0, emulated_hi = 0.0;
  bool emulated = false;

  void add(double ratio) {
    min = std::min(min, ratio);
    max = std::max(max, ratio);
    ++runs;
  }
  bool target_inside() const {
    return runs > 0 && target >= (emulated ? emulated_lo : min) &&
           target <= (emulated ? emulated_hi : max);
  }
};

}  // namespace rockcal::orch
