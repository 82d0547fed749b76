// Every evaluation of a calibration passes through the ledger: it clips the point into the bounds,
// answers repeated points from its own history (NLopt re-asks for its start), charges the budget,
// turns failures into a finite penalty, and records the history the report plots.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <stop_token>
#include <string>
#include <utility>
#include <vector>

#include "orchestrator/calibration/campaign.hpp"
#include "orchestrator/calibration/evaluator.hpp"
#include "orchestrator/calibration/objective.hpp"

namespace rockcal::calibration {

struct EvaluationRecord {
  int index = 0;                   // order of evaluation, from 0
  std::string phase;               // start | ratio | scale | local | scatter
  BondPoint point{};               // model units, as run
  std::uint64_t sample_seed = 0;   // of the first realisation
  std::optional<PeakLoads> loads;  // ensemble means; absent when the evaluation failed
  PeakLoads rel_se{0.0, 0.0};      // standard error / mean of each load (0 for one realisation)
  std::string error;
  std::optional<orch::Ensemble> uct;  // realisations and statistics, when the evaluator gave them
  std::optional<orch::Ensemble> btt;
  // The bayes strategy's further targets' peak loads at this run (model units, in the campaign's
  // `further` order); absent where a further test failed.
  std::vector<std::optional<double>> further_n;
  double misfit = 0.0;  // the objective; a penalty for a failed evaluation
  bool within_tolerance = false;
};

// Fills r's loads, errors, misfit and tolerance from an evaluator's outcome (r's index, phase,
// point and seed are the caller's); returns false for a failed evaluation, whose misfit the
// caller sets.
bool fill_record(EvaluationRecord& r, const EvaluationOutcome& outcome,
                 const CalibrationCampaign& campaign);

// The misfit a failed evaluation is given where nothing nearer says more: a factor 10 off on both
// loads.
double failure_floor(const CalibrationCampaign& campaign);

// Thrown (not an error) when the search must end: budget spent, or both targets met. It unwinds
// through NLopt and the strategies to the driver.
struct SearchDone {};

using RecordCallback = std::function<void(const EvaluationRecord&)>;

class Ledger {
 public:
  Ledger(const CalibrationCampaign& campaign, Evaluator& evaluator, std::stop_token stop,
         RecordCallback on_record);

  // Evaluates the points as one concurrent batch and returns their records in order. Throws
  // SearchDone once the targets are met or when the budget does not cover the batch (after
  // evaluating what it covers), EvaluationCancelled on a stop request.
  std::vector<EvaluationRecord> evaluate(const std::vector<BondPoint>& points,
                                         const std::string& phase);
  EvaluationRecord evaluate_one(const BondPoint& point, const std::string& phase);

  const std::vector<EvaluationRecord>& history() const { return history_; }
  const EvaluationRecord* best() const;  // lowest misfit among successful evaluations
  bool target_met() const;
  int remaining() const { return budget_ - int(history_.size()); }
  // After the search: `evaluations` more, which run on past a point that meets the targets (the
  // consistent-set trace looks for all such points, not the first).
  void extend_beyond_target(int evaluations);
  Weights weights() const { return {campaign_.weight_uct, campaign_.weight_btt}; }
  const PeakLoads& targets() const { return campaign_.targets.model_loads_n; }

 private:
  EvaluationRecord record(const BondPoint& point, const EvaluationOutcome& outcome,
                          const std::string& phase);
  double failure_penalty(const BondPoint& point) const;

  const CalibrationCampaign& campaign_;
  Evaluator& evaluator_;
  std::stop_token stop_;
  RecordCallback on_record_;
  std::vector<EvaluationRecord> history_;
  int budget_;
  bool stop_at_target_ = true;
  std::map<std::pair<double, double>, int> index_of_point_;
};

}  // namespace rockcal::calibration
