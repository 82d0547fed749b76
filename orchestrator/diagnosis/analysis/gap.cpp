#include "orchestrator/diagnosis/analysis/gap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "orchestrator/diagnosis/analysis/consistency.hpp"

namespace rockcal::diagnosis {

std::vector<double> ln_values(const RunOutcome& outcome) {
  std::vector<double> out;
  for (const auto& v : outcome.values) {
    out.push_back(v ? std::log(*v) : std::numeric_limits<double>::quiet_NaN());
  }
  return out;
}

std::vector<double> ln_lab(const std::vector<Target>& targets) {
  std::vector<double> out;
  for (const Target& t : targets) out.push_back(std::log(t.value));
  return out;
}

std::vector<double> residuals(const std::vector<double>& ln_sim,
                              const std::vector<double>& ln_lab) {
  std::vector<double> out(ln_sim.size());
  for (std::size_t i = 0; i < ln_sim.size(); ++i) out[i] = ln_sim[i] - ln_lab[i];
  return out;
}

std::vector<double> charged_residuals(const std::vector<double>& residuals,
                                      const std::vector<Target>& targets) {
  const std::vector<DataSpan> spans = data_spans(targets);
  std::vector<double> out = residuals;
  for (std::size_t i = 0; i < out.size() && i < spans.size(); ++i) {
    const DataSpan& s = spans[i];
    if (out[i] > s.hi) {
      out[i] -= s.hi;
    } else if (out[i] < s.lo) {
      out[i] -= s.lo;
    } else if (std::isfinite(out[i])) {
      out[i] = 0.0;
    }
  }
  return out;
}

std::optional<double> rms(const std::vector<double>& residuals, const std::vector<Target>& targets,
                          Role role) {
  const std::vector<double> r = charged_residuals(residuals, targets);
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (targets[i].role == role && std::isfinite(r[i])) {
      sum += r[i] * r[i];
      ++n;
    }
  }
  if (n == 0) return std::nullopt;
  return std::sqrt(sum / n);
}

double noise_scale(const Target& t, double budget, double fit_variance) {
  return std::sqrt(budget * budget + t.sigma * t.sigma + fit_variance);
}

double combined_budget(const std::vector<Target>& targets, const std::vector<double>& budget,
                       Role role) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (targets[i].role != role) continue;
    const double s = noise_scale(targets[i], budget[i]);
    sum += s * s;
    ++n;
  }
  return n ? std::sqrt(sum / n) : 0.0;
}

std::optional<double> rms_in_budgets(const std::vector<double>& residuals,
                                     const std::vector<Target>& targets,
                                     const std::vector<double>& budget, Role role,
                                     const std::vector<double>& fit_variance) {
  const std::vector<double> r = charged_residuals(residuals, targets);
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (targets[i].role != role || !std::isfinite(r[i])) continue;
    const double fit =
        i < fit_variance.size() && std::isfinite(fit_variance[i]) ? fit_variance[i] : 0.0;
    const double scale = std::max(noise_scale(targets[i], budget[i], fit), kMinNoiseScale);
    sum += (r[i] / scale) * (r[i] / scale);
    ++n;
  }
  if (n == 0) return std::nullopt;
  return std::sqrt(sum / n);
}

std::optional<double> gap_closure(std::optional<double> rms_effect,
                                  std::optional<double> rms_base) {
  if (!rms_effect || !rms_base || !(*rms_base > 0)) return std::nullopt;
  return 1.0 - *rms_effect / *rms_base;
}

std::optional<double> gap_closure_beyond_noise(std::optional<double> effect_budgets,
                                               std::optional<double> base_budgets) {
  if (!effect_budgets || !base_budgets || !(*base_budgets > 1.0)) return std::nullopt;
  const double left = std::sqrt(std::max(*effect_budgets * *effect_budgets - 1.0, 0.0));
  return 1.0 - left / std::sqrt(*base_budgets * *base_budgets - 1.0);
}

}  // namespace rockcal::diagnosis
