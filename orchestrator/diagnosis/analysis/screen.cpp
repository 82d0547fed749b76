#include "orchestrator/diagnosis/analysis/screen.hpp"

#include <cmath>
#include <cstdio>

#include "orchestrator/diagnosis/analysis/budget.hpp"

namespace rockcal::diagnosis {

ScreenedEffect screen_effect(std::string effect, const RunOutcome& base, const RunOutcome& strong,
                             const std::vector<std::array<double, 2>>& jacobian,
                             const std::vector<double>& weight, const std::vector<Target>& targets,
                             const std::vector<double>& budget) {
  const std::size_t n = targets.size();
  std::vector<double> raw(n, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < n; ++i) {
    const auto& b = base.values[i];
    const auto& s = strong.values[i];
    if (b && s) raw[i] = std::log(*s / *b);
  }
  ScreenedEffect out;
  out.effect = std::move(effect);
  out.change = change_after_refit(raw, jacobian, weight);
  for (std::size_t i = 0; i < n; ++i) {
    // Budget and lab uncertainty added, not in quadrature, as identifiability judges.
    out.noise.push_back(budget[i] + targets[i].sigma);
    if (!std::isfinite(out.change[i])) continue;
    const double in_noise = std::abs(out.change[i]) / out.noise[i];
    if (!out.largest || in_noise > out.largest_in_noise) {
      out.largest = i;
      out.largest_in_noise = in_noise;
    }
  }
  out.visible = !out.largest || out.largest_in_noise > 1.0;
  return out;
}

std::string screened_out_text(const std::vector<ScreenedEffect>& effects,
                              const std::vector<Target>& targets) {
  std::string names, near;
  int near_count = 0;
  for (const ScreenedEffect& e : effects) {
    if (e.visible) continue;
    names += (names.empty() ? "" : ", ") + e.effect;
    if (!e.largest || !(e.largest_in_noise >= kScreenNearThreshold)) continue;
    char line[256];
    std::snprintf(line, sizeof line, "%s moved %s %.2f of its noise at the %s", e.effect.c_str(),
                  targets[*e.largest].id.c_str(), e.largest_in_noise,
                  e.at_balanced ? "balanced point" : "base fit");
    near += std::string(near.empty() ? "" : ", ") + line;
    ++near_count;
  }
  if (names.empty()) return "";
  std::string out = "not tried, as invisible to these tests (screen): " + names;
  if (!near.empty()) {
    out += "; of these, " + near +
           ", near the threshold: data an effect raised put the base fit away from the strengths "
           "it would need, where its mark can be larger; a request with \"screen\": false "
           "designs " +
           (near_count > 1 ? "them" : "it");
  }
  return out;
}

std::array<double, 2> fit_shift(const RunOutcome& strong, const std::vector<Target>& targets,
                                const std::vector<std::array<double, 2>>& strong_jacobian,
                                const std::vector<double>& weight) {
  std::vector<double> residual(targets.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (strong.values[i] && *strong.values[i] > 0 && targets[i].value > 0)
      residual[i] = std::log(*strong.values[i] / targets[i].value);
  }
  const std::array<double, 2> dz = refit_shift(residual, strong_jacobian, weight);
  return {-dz[0], -dz[1]};
}

std::vector<std::array<double, 2>> secant_jacobian(const RunOutcome& at,
                                                   const std::array<RunOutcome, 2>& along,
                                                   const std::array<double, 2>& step) {
  const std::size_t n = at.values.size();
  std::vector<std::array<double, 2>> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 2; ++d) {
      const RunOutcome& o = along[std::size_t(d)];
      const std::optional<double> a = at.values[i];
      const std::optional<double> b = i < o.values.size() ? o.values[i] : std::nullopt;
      out[i][std::size_t(d)] = a && b && *a > 0 && *b > 0
                                   ? std::log(*b / *a) / step[std::size_t(d)]
                                   : std::numeric_limits<double>::quiet_NaN();
    }
  }
  return out;
}

}  // namespace rockcal::diagnosis
