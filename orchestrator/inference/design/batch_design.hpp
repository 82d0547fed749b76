// Where to run next: a batch of runs chosen where they most shrink the posterior.
//
// Why: the runs are the campaign's cost, and a run is worth what it removes from the answer's
// uncertainty. A run at c with one run's noise tau_j^2(c) lowers emulator j's variance at x by
// cov_j(x, c)^2 / (var_j(c) + tau_j^2(c)); what that does to the posterior at x depends on how much
// of the likelihood's variance the emulator holds there, var_j(x) / (sd_j^2 + var_j(x)). The value
// of c is that shrinkage summed over the targets and weighted by the posterior. Runs are picked
// one at a time, each picked run joining the pending ones (its variance reduction known before its
// value: the emulator's variance does not depend on it), so that a batch spreads out and a running
// batch is not designed again. A candidate that is an existing point is a further realisation
// there: with the packings' scatter large against the emulator's variance, that is where the next
// run is worth most, and the same rule chooses it. Where runs end without a result (the
// posterior's feasibility) a candidate's worth is scaled by its chance of giving one.
#pragma once

#include <vector>

#include "orchestrator/inference/posterior/posterior.hpp"

namespace rockcal::inference {

struct DesignInput {
  std::vector<const Gp*> emulators;  // one per target, at their fitted hyperparameters
  std::vector<Target> targets;
  const PosteriorGrid* posterior = nullptr;
  Eigen::MatrixXd candidates;  // c x d: where a run may go (new and existing points)
  Eigen::MatrixXd pending;     // p x d: runs submitted whose values are not yet known
  int batch = 1;               // runs to choose
  bool distinct = false;       // each candidate at most once (no replicates within the batch)
  int reference_cells = 400;   // the densest cells the shrinkage is summed over
};

struct DesignChoice {
  int candidate = 0;   // row of DesignInput::candidates
  double value = 0.0;  // its expected shrinkage when picked
};

// `batch` choices in the order picked (fewer when `distinct` runs out of candidates); a candidate
// may be picked more than once (replicates) unless `distinct`.
std::vector<DesignChoice> choose_batch(const DesignInput& input);

// The emulators' share of the posterior's variance, weighted by the posterior: for each target,
// sum_x w(x) var_j(x) / (sd_j^2 + disc_j^2). Below about 1/4 for every target, more runs would
// narrow the region by less than a tenth.
std::vector<double> emulator_share(const PosteriorGrid& posterior,
                                   const std::vector<Target>& targets);

}  // namespace rockcal::inference
