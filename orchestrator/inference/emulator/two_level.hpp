// Two resolutions in one emulator: the fine specimen's observable as the coarse emulator plus a
// fitted discrepancy.
//
// Why: at the lab's resolution a run costs minutes (a D/R 49 UCT several CPU minutes), so a
// calibration can afford a handful of fine runs besides a hundred coarse ones. A change of
// resolution moves the loads by nearly common factors over the strengths (the specimens' measured
// resolution trends), which in log space is a nearly constant shift: the fine observable is
// y_fine(x) = y_coarse(x) + d(x) with d smooth. The coarse emulator carries the shape; a GP on the
// fine runs' residuals from it (a constant or linear trend, lengths of at least the whole box by
// default, its own nugget = one fine run's scatter, learned from the fine replicates' spread as
// well as the residuals: with so few points the misfit alone would pass for scatter) carries d. The
// coarse emulator's variance at a fine point enters that point as known noise, and every prediction
// adds both emulators' means and variances, so the fine answer is as uncertain as the two together
// (Kennedy & O'Hagan 2000's autoregressive model with the scale fixed at 1, which homogeneity in
// log space makes the right one).
#pragma once

#include "orchestrator/inference/emulator/gp.hpp"

namespace rockcal::inference {

struct TwoLevelOptions {
  double min_length = 1.0;  // the discrepancy varies over the box, not between neighbours
  double max_length = 3.0;
};

// `fine` holds the fine runs' means at their points (runs and noise_var as for fit_gp). Needs at
// least 2 fine points; throws as fit_gp does.
Gp fit_two_level(const Gp& coarse, GpData fine, const TwoLevelOptions& options = {});

}  // namespace rockcal::inference
