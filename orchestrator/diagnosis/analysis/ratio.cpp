#include "orchestrator/diagnosis/analysis/ratio.hpp"

namespace rockcal::diagnosis {
namespace {

std::optional<std::size_t> first(const std::vector<Target>& targets, TestKind test,
                                 Observable observable) {
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const Target& t = targets[i];
    if (t.role == Role::calibration && t.conditions.test == test && t.observable == observable) {
      return i;
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<LabRatio> ratio_range(const std::vector<Target>& targets,
                                    const std::vector<RunOutcome>& base_grid) {
  for (Observable observable : {Observable::peak_load, Observable::strength}) {
    const auto uct = first(targets, TestKind::uct, observable);
    const auto btt = first(targets, TestKind::btt, observable);
    if (!uct || !btt) continue;
    LabRatio r{*uct, *btt, {.target = targets[*uct].value / targets[*btt].value}};
    for (const RunOutcome& o : base_grid) {
      if (o.values[*uct] && o.values[*btt]) r.range.add(*o.values[*uct] / *o.values[*btt]);
    }
    if (r.range.runs == 0) return std::nullopt;
    return r;
  }
  return std::nullopt;
}

}  // namespace rockcal::diagnosis
