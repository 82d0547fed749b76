#include "orchestrator/diagnosis/analysis/evidence.hpp"

#include <algorithm>
#include <cmath>

#include "orchestrator/diagnosis/analysis/gap.hpp"

namespace rockcal::diagnosis {

HeldOutDensity held_out_density(const std::vector<double>& residuals,
                                const std::vector<Target>& targets,
                                const std::vector<double>& budget,
                                const std::vector<double>& prediction_variance) {
  HeldOutDensity out;
  const std::vector<double> charged = charged_residuals(residuals, targets);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (targets[i].role != Role::held_out || !std::isfinite(charged[i])) continue;
    const double extra = prediction_variance.empty() ? 0.0 : prediction_variance[i];
    if (!std::isfinite(extra)) continue;
    const double scale = noise_scale(targets[i], budget[i], extra);
    const double v = std::max(scale * scale, kMinNoiseScale * kMinNoiseScale);
    const double r = charged[i];
    const double lpd = -0.5 * (r * r / v + std::log(2.0 * M_PI * v));
    out.terms.push_back({i, r, v, extra, lpd});
    out.lpd += lpd;
  }
  return out;
}

std::optional<double> evidence_over(const HeldOutDensity& model, const HeldOutDensity& base) {
  std::optional<double> sum;
  for (const DensityTerm& m : model.terms) {
    const auto b = std::find_if(base.terms.begin(), base.terms.end(),
                                [&](const DensityTerm& t) { return t.target == m.target; });
    if (b != base.terms.end()) sum = sum.value_or(0.0) + m.lpd - b->lpd;
  }
  return sum;
}

}  // namespace rockcal::diagnosis
