#include "orchestrator/calibration/reach.hpp"

#include <algorithm>

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
  const std::string emulated = a.ratio->emulated
                                   ? sentence("[%.4g, %.4g] by its emulators' means, single runs ",
                                              a.ratio->emulated_lo, a.ratio->emulated_hi)
                                   : "";
  return sentence("range %.3g: ", a.interaction_range) + emulated +
         sentence("[%.4g, %.4g] over ", a.ratio->min, a.ratio->max) +
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
  if (r.tried.size() == r.listed.size()) return out;
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
