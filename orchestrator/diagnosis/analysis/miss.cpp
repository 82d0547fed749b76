#include "orchestrator/diagnosis/analysis/miss.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "orchestrator/diagnosis/analysis/gap.hpp"

namespace rockcal::diagnosis {
namespace {

std::string printed(const char* format, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, x);
  return buf;
}

// "uct-1 (calibration) by -0.93 in ln (61% below the lab), 8.3 times its noise 0.112 (budget
// 0.100, lab uncertainty 0.050)"
std::string observation_text(const ObservationMiss& o) {
  const double percent = std::abs(100 * std::expm1(o.residual));
  const std::string side = o.residual == 0
                               ? "at the lab value"
                               : printed(percent >= 9.5 ? "%.0f%%" : "%.2g%%", percent) +
                                     (o.residual < 0 ? " below the lab" : " above the lab");
  return o.id + " (" + (o.role == Role::held_out ? "held out" : "calibration") + ") by " +
         printed("%+.2f", o.residual) + " in ln (" + side + "), " +
         printed("%.1f", o.in_budgets()) + " times its noise " + printed("%.3f", o.noise()) +
         " (budget " + printed("%.3f", o.budget) + ", lab uncertainty " + printed("%.3f", o.sigma) +
         (o.fit > 0 ? ", fit spread " + printed("%.3f", o.fit) : std::string()) + ")";
}

std::string rms_text(const ModelMiss& m) {
  std::string out;
  if (m.calibration) {
    out += "rms " + printed("%.1f", *m.calibration) +
           " noise budgets over the calibration observations";
  }
  if (m.held_out) {
    out += std::string(out.empty() ? "rms " : ", ") + printed("%.1f", *m.held_out) +
           " over the held-out ones";
  }
  return out;
}

}  // namespace

double ObservationMiss::noise() const {
  Target t;
  t.sigma = sigma;
  return std::max(noise_scale(t, budget, fit * fit), kMinNoiseScale);
}

double ObservationMiss::in_budgets() const {
  return std::abs(residual) / noise();
}

ModelMiss model_miss(std::string model, const std::vector<Target>& targets,
                     const std::vector<double>& residuals, const std::vector<double>& budget,
                     const std::vector<double>& fit_variance, double beyond) {
  ModelMiss m;
  m.model = std::move(model);
  m.calibration = rms_in_budgets(residuals, targets, budget, Role::calibration, fit_variance);
  m.held_out = rms_in_budgets(residuals, targets, budget, Role::held_out, fit_variance);
  const std::vector<double> charged = charged_residuals(residuals, targets);
  for (std::size_t i = 0; i < targets.size() && i < charged.size(); ++i) {
    if (!std::isfinite(charged[i])) continue;
    const double fit = i < fit_variance.size() && std::isfinite(fit_variance[i])
                           ? std::sqrt(std::max(fit_variance[i], 0.0))
                           : 0.0;
    const ObservationMiss o{targets[i].id, targets[i].role,  charged[i],
                            budget[i],     targets[i].sigma, fit};
    if (o.in_budgets() > beyond) m.beyond.push_back(o);
    if (!m.largest || o.in_budgets() > m.largest->in_budgets()) m.largest = o;
  }
  return m;
}

bool misses_beyond(const ModelMiss& m, double limit) {
  return m.calibration.value_or(0) > limit || m.held_out.value_or(0) > limit;
}

std::string miss_text(const ModelMiss& m, double beyond) {
  if (!m.largest) return m.model + " has no residual to state (its runs failed)";
  std::string out;
  if (m.beyond.empty()) {
    out = m.model + " meets every observation within " + printed("%.2f", beyond) +
          " noise budgets (the furthest: " + observation_text(*m.largest) + ")";
  } else {
    out = m.model + " misses ";
    for (std::size_t k = 0; k < m.beyond.size(); ++k) {
      out += (k == 0                     ? ""
              : k + 1 == m.beyond.size() ? ", and "
                                         : ", ") +
             observation_text(m.beyond[k]);
    }
  }
  const std::string rms = rms_text(m);
  return rms.empty() ? out : out + ": " + rms;
}

}  // namespace rockcal::diagnosis
