// The calibration driver: one campaign, one optimiser thread.
//
//   CalibrationCampaign c = parse_calibration_campaign(body);      // orch::RequestError -> 400
//   CalibrationThread run(c, my_evaluator, on_evaluation);         // starts the thread
//   run.cancel();                                                  // DELETE: stop soon
//   nlohmann::json report = to_json(run.wait(), c);                // joins
//
// Determinism: for a given campaign and evaluator answers, the sequence of requested points is
// fixed (fixed start design, seeded Latin hypercube, nlopt::srand, no clocks), so a restarted
// campaign replays its history from the job cache and continues where it stopped.
#pragma once

#include <functional>
#include <future>
#include <stop_token>
#include <thread>

#include "orchestrator/calibration/campaign.hpp"
#include "orchestrator/calibration/evaluator.hpp"
#include "orchestrator/calibration/ledger.hpp"
#include "orchestrator/calibration/report.hpp"

namespace rockcal::calibration {

struct RunOptions {
  std::stop_token stop;          // checked before every batch
  RecordCallback on_evaluation;  // after each search evaluation (progress, persistence)
  int workers = 2;               // the pool's: a batch design keeps this many busy
  // After the stiffness stage, before the strength search (E or nu a target only).
  std::function<void(const StiffnessResult&)> on_stiffness = {};
};

// Runs the whole calibration in the calling thread and returns its report; a cancellation (stop
// request or EvaluationCancelled from the evaluator) returns the partial report. Other exceptions
// from the evaluator (infrastructure failures) propagate.
CalibrationReport run_calibration(const CalibrationCampaign& campaign, Evaluator& evaluator,
                                  const RunOptions& options = {});

// run_calibration on its own thread. The evaluator must outlive the object.
class CalibrationThread {
 public:
  CalibrationThread(CalibrationCampaign campaign, Evaluator& evaluator,
                    RecordCallback on_evaluation = {}, int workers = 2);
  ~CalibrationThread();  // cancels and joins
  CalibrationThread(const CalibrationThread&) = delete;
  CalibrationThread& operator=(const CalibrationThread&) = delete;

  // Requests a stop; an evaluation in flight ends when the evaluator returns or throws
  // EvaluationCancelled (the evaluator may poll stop_token() to cut its wait short).
  void cancel() { thread_.request_stop(); }
  std::stop_token stop_token() const { return thread_.get_stop_token(); }
  // Waits for the end and returns the report (or rethrows the driver's exception). Once only.
  CalibrationReport wait();

 private:
  CalibrationCampaign campaign_;
  std::promise<CalibrationReport> promise_;
  std::future<CalibrationReport> result_;
  std::jthread thread_;
};

}  // namespace rockcal::calibration
