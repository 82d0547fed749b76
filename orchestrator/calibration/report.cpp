#include "orchestrator/calibration/report.hpp"

#include <algorithm>
#include <cmath>

namespace rockcal::calibration {
namespace {

std::optional<LoadStats> stats(const std::vector<ScatterRun>& runs, double PeakLoads::*load) {
  std::vector<double> x;
  for (const ScatterRun& r : runs) {
    if (r.loads) x.push_back((*r.loads).*load);
  }
  if (x.empty()) return std::nullopt;
  LoadStats s;
  s.runs = int(x.size());
  for (double v : x) s.mean_n += v / x.size();
  double ss = 0.0;
  for (double v : x) ss += (v - s.mean_n) * (v - s.mean_n);
  s.stddev_n = x.size() > 1 ? std::sqrt(ss / (x.size() - 1)) : 0.0;
  return s;
}

}  // namespace

std::optional<RatioRange> ratio_range(const std::vector<EvaluationRecord>& history,
                                      const PeakLoads& targets) {
  std::optional<RatioRange> range;
  for (const EvaluationRecord& r : history) {
    if (!r.loads) continue;
    const double ratio = r.loads->uct_n / r.loads->btt_n;
    if (!range) range = RatioRange{targets.uct_n / targets.btt_n, ratio, ratio, false};
    range->min = std::min(range->min, ratio);
    range->max = std::max(range->max, ratio);
  }
  if (range) range->target_inside = range->target >= range->min && range->target <= range->max;
  return range;
}

SeedScatter seed_scatter(std::vector<ScatterRun> runs) {
  SeedScatter s;
  s.uct = stats(runs, &PeakLoads::uct_n);
  s.btt = stats(runs, &PeakLoads::btt_n);
  s.runs = std::move(runs);
  return s;
}

const char* to_string(StopReason reason) {
  switch (reason) {
    case StopReason::tolerance_met:
      return "tolerance_met";
    case StopReason::budget_exhausted:
      return "budget_exhausted";
    case StopReason::converged:
      return "converged";
    case StopReason::cancelled:
      return "cancelled";
  }
  return "?";
}

const char* to_string(Verdict verdict) {
  switch (verdict) {
    case Verdict::feasible:
      return "feasible";
    case Verdict::compromise:
      return "compromise";
    case Verdict::incomplete:
      return "incomplete";
    case Verdict::failed:
      return "failed";
  }
  return "?";
}

}  // namespace rockcal::calibration
