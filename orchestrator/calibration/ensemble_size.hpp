// How many packings each evaluation runs. One packing's peak load is one draw of the lattice cut;
// the tolerance test needs the ensemble mean's standard error well below the tolerance, so with
// "realisations": "auto" the size comes from a pilot ensemble at the first start point: the least
// n with CV / sqrt(n) <= tolerance / 2 for both tests, within "max_realisations". Whatever the
// choice, the report says what size the scatter calls for, from the pilot and again from the best
// point's own ensemble, and what standard error the size run leaves.
#pragma once

#include <optional>
#include <string>

#include "orchestrator/calibration/campaign.hpp"
#include "orchestrator/calibration/evaluator.hpp"
#include "orchestrator/calibration/ledger.hpp"

namespace rockcal::calibration {

struct ScatterEstimate {
  std::optional<double> cv_uct;  // sample sd / mean of the peak loads (>= 2 realisations)
  std::optional<double> cv_btt;
  int runs = 0;               // realisations of the smaller of the two ensembles
  std::optional<int> needed;  // realisations for se <= tolerance / 2 on both tests
};

struct EnsembleSize {
  bool automatic = false;
  int realisations = 1;     // per evaluation, as run
  bool capped = false;      // the scatter called for more than max_realisations
  ScatterEstimate pilot;    // automatic only: the pilot's (at the first start point)
  ScatterEstimate at_best;  // the best point's own ensemble (or its seed re-runs), after the search
  std::string why;          // one sentence on the choice and what standard error it leaves
};

// Realisations that bring the standard error of an ensemble mean of coefficient of variation cv
// to half the tolerance.
int realisations_for(double cv, double tolerance);

ScatterEstimate scatter_estimate(std::optional<double> cv_uct, std::optional<double> cv_btt,
                                 int runs, double tolerance);
ScatterEstimate scatter_estimate(const std::optional<orch::Ensemble>& uct,
                                 const std::optional<orch::Ensemble>& btt, double tolerance);

// Runs the pilot when the campaign asks for "auto" (its runs are cached, so the evaluations that
// follow at that point reuse them); otherwise records the campaign's fixed size.
EnsembleSize choose_ensemble_size(const CalibrationCampaign& c, Evaluator& evaluator);

// After the search: what the best point's ensemble says (or, with one packing per evaluation,
// the best point's re-runs on other seeds: `scatter`), and the sentence for the report.
void review_ensemble_size(EnsembleSize& size, const EvaluationRecord* best,
                          const std::optional<ScatterEstimate>& scatter, double tolerance);

}  // namespace rockcal::calibration
