// What the "bayes" strategy answers: the posterior of (F_r0, F_s0) given the two targets, in the
// campaign's model units. Every figure here comes from the emulators and runs of the campaign.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "orchestrator/calibration/campaign.hpp"
#include "orchestrator/calibration/evaluator.hpp"

namespace rockcal::calibration {

// The check runs at the estimate against the prediction there (bayes/check.hpp).
struct CheckAgreement {
  int n = 0;                            // successful check runs
  double mean_n = 0.0;                  // their geometric mean
  double predicted_n = 0.0;             // the predicted mean they are judged against
  double relative_to_prediction = 0.0;  // mean_n / predicted_n - 1
  double relative_to_target = 0.0;      // mean_n / target - 1
  double sd = 0.0;                      // the sd of ln(mean_n) the prediction allows
  double z = 0.0;                       // ln(mean_n / predicted mean) / sd
  bool agrees = true;                   // |z| within the 99% quantile
};

// One target's prediction at the estimate: the emulator's mean of the ensemble-mean load, its
// `level` interval, and the interval one more packing's run would fall in.
struct PredictedLoad {
  double target_n = 0.0;
  double mean_n = 0.0;
  double lo_n = 0.0, hi_n = 0.0;          // the ensemble mean's interval
  double run_lo_n = 0.0, run_hi_n = 0.0;  // one packing's interval
  double relative_error = 0.0;            // mean / target - 1
  double lab_sd = 0.0;                    // the target's relative sd used
  double emulator_sd = 0.0;               // sd of ln(mean) from the emulator at the estimate
  double run_sd = 0.0;                    // sd of ln(load) of one packing (the pooled scatter)
  double emulator_share = 0.0;            // posterior-weighted emulator variance / lab variance
  std::optional<CheckAgreement> check;    // the check runs', once they ran
};

// A row of the region's cells on the posterior's grid: cells [i_lo, i_hi] of F_r0 at F_s0 row j.
struct RegionSpan {
  int j = 0, i_lo = 0, i_hi = 0;
};

struct PosteriorSummary {
  double level = 0.9;
  BondPoint estimate{};                      // the posterior's density peak
  Range fr0{0, 0}, fs0{0, 0};                // marginal `level` intervals
  Range fr0_extent{0, 0}, fs0_extent{0, 0};  // the region's extent
  // The marginal intervals with the emulators exact: the narrowest more runs can make them at the
  // targets' stated uncertainty (inference::with_exact_emulators).
  Range fr0_exact{0, 0}, fs0_exact{0, 0};
  // The strength bounds (the fine specimen's when fine) and the grid the region is drawn on:
  // grid_cells per dimension, log-spaced over where the posterior's mass lies within the bounds
  // (inference::zoomed_grid).
  Range box_fr0{0, 0}, box_fs0{0, 0};
  int grid_cells = 0;
  Range grid_fr0{0, 0}, grid_fs0{0, 0};
  std::vector<RegionSpan> region;           // the highest-density cells holding `level`
  std::vector<std::string> bounds_reached;  // e.g. "the upper bound of F_s0 (1000)"
  PredictedLoad uct, btt;
  std::vector<PredictedLoad> further;  // the further targets', in the campaign's order
  bool lab_stated = false;
  double discrepancy = 0.0;
  double unique_width = 1.5;
  bool unique = false;
  std::string why;  // the reason for `unique`, a sentence
  int runs = 0;     // successful runs the emulators were fitted to (fine runs when fine)
  // "fine" when the posterior is the fine specimen's (two-level emulators over coarse_runs coarse
  // runs and `runs` fine ones), "coarse" when a campaign with a fine specimen has no fine
  // emulator (its fine runs failed), empty for one specimen.
  std::string resolution;
  int coarse_runs = 0;
  int points = 0;  // distinct points among them
  int rounds = 0;  // batches designed after the start
  // Where the check runs ran: the estimate before them. Fitted on them too, the posterior may put
  // its estimate elsewhere, where no run has been made; `estimate` then differs from it.
  std::optional<BondPoint> checked_at;
  // Why the check runs gave no loads (their error, e.g. a UCT without a peak); empty when they
  // gave both or none ran. The estimate's prediction then has no run to bear it out.
  std::string check_failed;
  // The estimate moved after the check runs by more than kCheckedSpread (relative) in either
  // strength: the check runs then say how the emulators did at the point before, not at this one.
  static constexpr double kCheckedSpread = 0.02;
  bool estimate_moved() const {
    return checked_at && (std::abs(estimate.fr0_n / checked_at->fr0_n - 1.0) > kCheckedSpread ||
                          std::abs(estimate.fs0_n / checked_at->fs0_n - 1.0) > kCheckedSpread);
  }
};

}  // namespace rockcal::calibration
