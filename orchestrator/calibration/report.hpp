// What a calibration found: the GET /api/v1/campaigns/{id} payload of a calibration campaign.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "orchestrator/calibration/bayes/summary.hpp"
#include "orchestrator/calibration/campaign.hpp"
#include "orchestrator/calibration/ensemble_size.hpp"
#include "orchestrator/calibration/fidelity.hpp"
#include "orchestrator/calibration/homogeneity.hpp"
#include "orchestrator/calibration/ledger.hpp"
#include "orchestrator/calibration/reach.hpp"
#include "orchestrator/calibration/stiffness.hpp"
#include "orchestrator/calibration/suggestion.hpp"
#include "orchestrator/ratio_range.hpp"

namespace rockcal::calibration {

// answered (bayes): the credible region was unique with both predicted loads within the tolerance
// over the last runs, so the budget left was not spent.
enum class StopReason { tolerance_met, budget_exhausted, converged, answered, cancelled };
// feasible: both loads within tolerance. compromise: the search ended without that (the reason
// says whether the target ratio is out of the model's reach). incomplete: cancelled first.
// failed: no evaluation succeeded.
enum class Verdict { feasible, compromise, incomplete, failed };

// UCT/BTT load ratios the model reached over all successful evaluations, vs the targets'.
using orch::RatioRange;

struct ScatterRun {
  std::uint64_t seed = 0;
  std::optional<PeakLoads> loads;
  std::string error;
};

struct LoadStats {
  double mean_n = 0.0;
  double stddev_n = 0.0;  // sample standard deviation over the seeds
  int runs = 0;
};

// The best point re-run on other packings: an uncertainty, not a single lucky run.
struct SeedScatter {
  std::vector<ScatterRun> runs;  // the search's own seed first
  std::optional<LoadStats> uct;
  std::optional<LoadStats> btt;
};

struct CalibrationReport {
  ValleyTrace trace;                       // the consistent-set trace after the search
  ConsistentSet consistent;                // every evaluated point that meets the targets
  std::optional<Suggestion> suggestion;    // when the set is not one point
  std::optional<FidelityResult> fidelity;  // the fine specimen's corrections, when asked for
  StopReason stop_reason = StopReason::converged;
  Verdict verdict = Verdict::failed;
  std::string verdict_reason;
  std::string strategy_used;  // ratio_scale | ratio_scale+direct_2d | direct_2d | none
  HomogeneityChecks homogeneity;
  std::optional<EvaluationRecord> best;
  std::vector<EvaluationRecord> history;
  std::optional<RatioRange> ratio;  // absent without a successful evaluation
  SeedScatter scatter;
  EnsembleSize ensemble;  // packings per evaluation: how many, why, what the scatter calls for
  std::optional<PosteriorSummary> posterior;  // the "bayes" strategy's answer
  std::optional<StiffnessResult> stiffness;   // the stiffness stage, when E or nu is a target
  // The interaction ranges tried ("reach" in the request); `history` is the last range's runs.
  std::optional<ReachResult> reach;
};

std::optional<RatioRange> ratio_range(const std::vector<EvaluationRecord>& history,
                                      const PeakLoads& targets_n);

// The ratios a range reached, as a verdict words them: "the range [a, b] the runs reached", or,
// when the emulators judged the reach, theirs with the single runs' beside it.
std::string reach_words(const RatioRange& r);
SeedScatter seed_scatter(std::vector<ScatterRun> runs);

const char* to_string(StopReason reason);
const char* to_string(Verdict verdict);

// The report as JSON: model units throughout, plus "lab" blocks when the targets were in lab units.
nlohmann::json to_json(const CalibrationReport& report, const CalibrationCampaign& campaign);

// What a running calibration can show: its history so far (for a live convergence plot).
nlohmann::json progress_json(const std::vector<EvaluationRecord>& history,
                             const CalibrationCampaign& campaign);

}  // namespace rockcal::calibration
