// The third parameter: the interaction range (the engine's `interaction_range` effect, bonds
// between all pairs within factor x (R_i + R_j)) as a staged outer loop around the strength
// search. With "reach": {"interaction_range": [1, 1.5]} the calibration runs at the first range;
// when its runs show the target UCT/BTT load ratio outside the ratios they reached (ratio_range),
// it moves to the next range with the budget left, redoing the stiffness stage there (the range
// multiplies E). When the last listed range's runs come no nearer the target ratio than an earlier
// range's did, the calibration goes back to the nearest one with the budget left and answers there
// (a softer lattice that meets a nu target can reach less far than touching bonds). docs/reach.md
// maps which ratios each range reaches.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "orchestrator/calibration/ledger.hpp"
#include "orchestrator/ratio_range.hpp"

namespace rockcal::calibration {

// The fewest evaluations a range is tried with (the request's least max_evaluations).
inline constexpr int kReachMinEvaluations = 4;

// The calibration's runs at one interaction range.
struct ReachAttempt {
  double interaction_range = 1.0;
  std::vector<EvaluationRecord> history;  // the runs there (the last range's are the report's)
  std::optional<orch::RatioRange> ratio;  // the UCT/BTT load ratios they reached
};

struct ReachResult {
  std::vector<double> listed;       // the request's ranges, in order
  std::vector<ReachAttempt> tried;  // the last is the range the answer is at
  int evaluations_left = 0;         // of the budget when the last range ended
  bool cancelled = false;           // the calibration was cancelled at the last range
  bool went_back = false;           // the last attempt is a return to the range that came nearest
  std::string why;                  // a sentence from the fields above
};

// Whether the runs so far at a range send the calibration on to the next, from the ratios they
// reached and how many they were (the driver's leave_range with its budget).
using LeaveRange = std::function<bool(const std::optional<orch::RatioRange>& ratio, int runs)>;

// The runs a search that would otherwise spend the whole budget (the "bayes" strategy) makes at a
// range before the ratios they reached may send it on: a quarter of the budget, at least the
// start batch's 8. The ratios reached only widen with more runs, so after that the question is
// asked after every batch.
int reach_probe_runs(int max_evaluations);

// The patch of "job" that runs a range: {"effects": {"interaction_range": {"factor": x}}}.
nlohmann::json interaction_range_patch(double factor);

// Whether the runs at a range send the calibration on to the next: the target ratio lies outside
// what they reached, another range is listed, and at least kReachMinEvaluations are left for it.
bool leave_range(const std::optional<orch::RatioRange>& ratio, bool another_listed, int left);

// How far the target UCT/BTT load ratio lies outside the ratios reached, in ln (0 inside);
// infinite without a ratio.
double ratio_distance(const std::optional<orch::RatioRange>& ratio);

// The earlier attempt whose runs came nearest the target ratio (the first of equals), or -1 when
// none gave a ratio.
int nearest_attempt(const std::vector<ReachAttempt>& earlier);

// Whether the runs at the last listed range send the calibration back to an earlier one: the
// target ratio lies outside what they reached, they came no nearer it than the nearest earlier
// range's, and at least kReachMinEvaluations are left.
bool go_back(const std::optional<orch::RatioRange>& ratio, const std::vector<ReachAttempt>& earlier,
             int left);

// The reason: the range used, and the ratios the runs reached at each range tried.
std::string reach_why(const ReachResult& reach, double target_ratio);

}  // namespace rockcal::calibration
