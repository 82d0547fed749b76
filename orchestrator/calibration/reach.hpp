// The third parameter: the interaction range (the engine's `interaction_range` effect, bonds
// between all pairs within factor x (R_i + R_j)) as a staged outer loop around the strength
// search. With "reach": {"interaction_range": [1, 1.5]} the calibration runs at the first range;
// when its runs show the target UCT/BTT load ratio outside the ratios they reached (ratio_range),
// it moves to the next range with the budget left, redoing the stiffness stage there (the range
// multiplies E). docs/reach.md maps which ratios each range reaches.
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

// The reason: the range used, and the ratios the runs reached at each range tried.
std::string reach_why(const ReachResult& reach, double target_ratio);

}  // namespace rockcal::calibration
