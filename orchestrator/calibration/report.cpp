#include "orchestrator/calibration/report.hpp"

#include <algorithm>
#include <cmath>

#include "orchestrator/calibration/sentence.hpp"

namespace rockcal::calibration {
namespace {

std::optional<LoadStats> stats(const std::vector<ScatterRun>& runs, double PeakLoads::*load) {
  std::vector<double> x;
  for (const ScatterRun& r : runs) {
    if (r.loads) x.push_back((*r.loads).*load);
  }
  const orch::SampleStats s = orch::sample_stats(x);
  if (!s.mean) return std::nullopt;
  return LoadStats{*s.mean, s.sd.value_or(0.0), s.n};
}

}  // namespace

std::optional<RatioRange> ratio_range(const std::vector<EvaluationRecord>& history,
                                      const PeakLoads& targets) {
  RatioRange range{.target = targets.uct_n / targets.btt_n};
  for (const EvaluationRecord& r : history) {
    if (r.loads) range.add(r.loads->uct_n / r.loads->btt_n);
  }
  if (range.runs == 0) return std::nullopt;
  return range;
}

std::string reach_words(const RatioRange& r) {
  if (!r.emulated) return sentence("the range [%.4g, %.4g] the runs reached", r.min, r.max);
  return sentence(
      "the range [%.4g, %.4g] the emulators' means give at the points run (single "
      "runs, with their packings' scatter, reached [%.4g, %.4g])",
      r.emulated_lo, r.emulated_hi, r.min, r.max);
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
    case StopReason::answered:
      return "answered";
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
