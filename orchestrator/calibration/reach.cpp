#include "orchestrator/calibration/reach.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "orchestrator/calibration/run_faults.hpp"
#include "orchestrator/calibration/sentence.hpp"

namespace rockcal::calibration {
namespace {

std::string attempt_text(const ReachAttempt& a) {
  if (!a.ratio) {
    const std::string faults = no_peak_text(a.history);
    return sentence("range %.3g: no run gave both loads (%.0f evaluations", a.interaction_range,
                    double(a.history.size())) +
           (faults.empty() ? ")" : "; " + faults + ")");
  }
  return sentence("range %.3g: [%.4g, %.4g] over ", a.interaction_range, a.ratio->min,
                  a.ratio->max) +
         sentence("%.0f runs", double(a.history.size()));
}

}  // namespace

nlohmann::json interaction_range_patch(double factor) {
  return {{"effects", {{"interaction_range", {{"factor", factor}}}}}};
}

int reach_probe_runs(int max_evaluations) {
  return std::max(8, max_evaluations / 4);
}

bool leave_range(const std::optional<orch::RatioRange>& ratio, bool another_listed, int left) {
  return another_listed && ratio && !ratio->target_inside() && left >= kReachMinEvaluations;
}

double ratio_distance(const std::optional<orch::RatioRange>& ratio) {
  if (!ratio || ratio->runs == 0) return std::numeric_limits<double>::infinity();
  if (ratio->target > ratio->max) return std::log(ratio->target / ratio->max);
  if (ratio->target < ratio->min) return std::log(ratio->min / ratio->target);
  return 0.0;
}

int nearest_attempt(const std::vector<ReachAttempt>& earlier) {
  int best = -1;
  for (std::size_t i = 0; i < earlier.size(); ++i) {
    if (!earlier[i].ratio) continue;
    if (best < 0 || ratio_distance(earlier[i].ratio) < ratio_distance(earlier[best].ratio))
      best = int(i);
  }
  return best;
}

bool go_back(const std::optional<orch::RatioRange>& ratio, const std::vector<ReachAttempt>& earlier,
             int left) {
  const int nearest = nearest_attempt(earlier);
  return ratio && !ratio->target_inside() && nearest >= 0 && left >= kReachMinEvaluations &&
         ratio_distance(ratio) >= ratio_distance(earlier[nearest].ratio);
}

std::string reach_why(const ReachResult& r, double target_ratio) {
  if (r.tried.empty()) return "";
  std::string list;
  for (const ReachAttempt& a : r.tried) list += (list.empty() ? "" : "; ") + attempt_text(a);
  const ReachAttempt& used = r.tried.back();
  const bool inside = used.ratio && used.ratio->target_inside();
  if (inside && r.tried.size() == 1) {
    return sentence(
               "interaction range %.3g, the first listed: its runs reached the target UCT/BTT "
               "load ratio %.4g (",
               used.interaction_range, target_ratio) +
           list + ")";
  }
  if (inside) {
    return sentence(
               "interaction range %.3g: the target UCT/BTT load ratio %.4g lay outside the "
               "ratios the runs reached at the ranges before it, inside this one's (",
               used.interaction_range, target_ratio) +
           list + ")";
  }
  std::string out =
      sentence("no interaction range tried reaches the target UCT/BTT load ratio %.4g (",
               target_ratio) +
      list + ")";
  if (r.went_back && r.tried.size() >= 2) {
    const ReachAttempt& last_listed = r.tried[r.tried.size() - 2];
    return out +
           sentence("; range %.3g came no nearer it than range %.3g, ",
                    last_listed.interaction_range, used.interaction_range) +
           sentence("so the calibration went back to range %.3g with the budget left",
                    used.interaction_range);
  }
  if (r.tried.size() >= r.listed.size()) return out;
  const double next = r.listed[r.tried.size()];
  if (r.cancelled) return out + sentence("; range %.3g not tried: cancelled", next);
  if (!used.ratio) {
    return out + sentence("; range %.3g not tried: no run at range %.3g gave a ratio to compare",
                          next, used.interaction_range);
  }
  return out +
         sentence("; range %.3g not tried: %.0f evaluations of the budget were left, ", next,
                  double(r.evaluations_left)) +
         sentence("fewer than %.0f", kReachMinEvaluations);
}

}  // namespace rockcal::calibration
