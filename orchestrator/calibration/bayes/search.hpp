// The "bayes" strategy: the calibration as inference (orchestrator/inference/).
//
// Why: one packing's peak loads scatter by more than the tolerance, so a search that minimises
// the misfit of single runs chases noise, and ensembles at every point are too dear. Here every
// run is one packing (a seed of its own), both loads' emulators pool all runs, and the answer is
// the posterior of (F_r0, F_s0) given the targets with the lab's uncertainty, the emulators'
// variance and the packings' scatter in it.
//
// The loop keeps the pool full: a space-filling start, then batches of `batch` runs (the pool's
// workers by default) chosen where they most shrink the posterior, two batches in flight so that
// the next is queued while the last one's results are read (a batch is designed with the running
// one's points as pending). It ends when the emulators hold less than a quarter of the
// posterior's variance or the budget is spent, with a check batch: the estimate on `batch`
// packings. Deterministic for given outcomes (fixed start, seeds by run index, no clocks), so a
// restarted campaign replays from the job cache.
#pragma once

#include "orchestrator/calibration/driver.hpp"
#include "orchestrator/calibration/reach.hpp"

namespace rockcal::calibration {

// Fills report.history, best (the check batch at the estimate, as one ensemble), posterior,
// stop_reason, verdict and verdict_reason. Throws what the evaluator throws, but for
// EvaluationCancelled, which ends the search with what it has.
// With `leave` (a reach's range that is not the last), the search stops once its runs, at least
// reach_probe_runs of them, send the calibration on: report.history and ratio are filled, and no
// check batch, posterior or verdict is made for a range the answer will not be at. Returns whether
// it left (decided once, on the runs the search had then: the runs still in flight, taken after,
// do not undo it).
bool bayes_calibration(const CalibrationCampaign& campaign, Evaluator& evaluator,
                       const RunOptions& options, CalibrationReport& report,
                       const LeaveRange& leave = {});

}  // namespace rockcal::calibration
