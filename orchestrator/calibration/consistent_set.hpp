// The set of bond strengths consistent with the targets. Two peak loads need not pin two strengths:
// where both loads depend on one combination of F_r0 and F_s0 (a bond that fails by its weaker
// mode, a mechanism that saturates), a whole curve of the (F_r0, F_s0) plane meets both, and the
// search's answer is one member of it. The seed paper warned of this ("not a unique combination of
// parameters"); a user must be told. So after the search the trace walks from the best point along
// the valley, one ratio s = ln(F_s0/F_r0) at a time in steps of kRatioStep, each at the scale that
// best fits both loads, until a ratio that no scale fits (or the bounds, or its budget) ends each
// direction.
#pragma once

#include <string>
#include <vector>

#include "orchestrator/calibration/ledger.hpp"

namespace rockcal::calibration {

// Steps of F_s0/F_r0 along the valley. With both directions closed by a miss one step from the
// best point, every consistent point lies within a factor 1.2 of its ratio, so each strength lies
// within a factor 1.2 of the best point's (about 10% each where the step shares out between the
// two; the whole step in one strength where the other is pinned by a load): the uniqueness the
// report claims is at this resolution.
inline constexpr double kRatioStep = 1.2;
// A set is one point when each strength spans at most this relative half-width.
inline constexpr double kUniqueHalfWidth = 0.1;

// How one direction of the walk ended.
enum class TraceEnd { not_traced, missed, bounds, budget, failed };

struct ValleyTrace {
  TraceEnd up = TraceEnd::not_traced;    // toward larger F_s0/F_r0
  TraceEnd down = TraceEnd::not_traced;  // toward smaller
  int branches = 0;      // separate ratios found to meet the targets (0: not traced)
  bool scanned = false;  // the other ratios within the bounds were scanned for further branches
  int evaluations = 0;
};

// Walks the valley from the ledger's best point when it meets the targets, spending at most
// `budget` evaluations (phase "valley"); `degree` is the measured homogeneity degree (1 without a
// measurement). Throws EvaluationCancelled like the ledger.
ValleyTrace trace_valley(Ledger& ledger, const CalibrationCampaign& campaign, double degree,
                         int budget);

struct ConsistentSet {
  std::vector<EvaluationRecord> points;     // evaluated and within tolerance + standard error
  Range fr0{0, 0}, fs0{0, 0}, ratio{0, 0};  // spans of the points (model units; ratio fs0/fr0)
  bool unique = false;
  std::string why;  // the reason for `unique`, a sentence
};

ConsistentSet consistent_set(const std::vector<EvaluationRecord>& history,
                             const ValleyTrace& trace);

const char* to_string(TraceEnd end);

}  // namespace rockcal::calibration
