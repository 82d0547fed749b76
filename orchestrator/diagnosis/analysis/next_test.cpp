#include "orchestrator/diagnosis/analysis/next_test.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "orchestrator/diagnosis/analysis/budget.hpp"

namespace rockcal::diagnosis {

double TestNoise::total() const {
  return std::hypot(budget, sigma);
}

TestNoise borrowed_noise(const Target& test, const std::vector<Target>& targets,
                         const std::vector<double>& budget) {
  // The closest kin the dataset has: 2 the same test and observable, 1 the same test, 0 any.
  auto kinship = [&](const Target& t) {
    if (t.conditions.test != test.conditions.test) return 0;
    return t.observable == test.observable ? 2 : 1;
  };
  int closest = 0;
  for (const Target& t : targets) closest = std::max(closest, kinship(t));
  TestNoise n;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const Target& t = targets[i];
    if (kinship(t) != closest) continue;
    if (std::isfinite(budget[i]) && (n.budget_from.empty() || budget[i] > n.budget)) {
      n.budget = budget[i];
      n.budget_from = t.id;
    }
    if (n.sigma_from.empty() || t.sigma > n.sigma) {
      n.sigma = t.sigma;
      n.sigma_from = t.id;
    }
  }
  return n;
}

void use_measured_budgets(std::vector<TestNoise>& noise, const Budget& measured, std::size_t n) {
  for (std::size_t m = 0; m < noise.size(); ++m) {
    if (n + m >= measured.measured.size() || !measured.measured[n + m]) continue;
    noise[m].budget = measured.per_target[n + m];
    noise[m].budget_from.clear();
    noise[m].measured_by.clear();
    for (std::size_t v = 0; v < measured.variants.size(); ++v) {
      if (std::isfinite(measured.change[v][n + m]))
        noise[m].measured_by.push_back(measured.variants[v].name);
    }
  }
}

Separation separate(std::string a, std::string b, const std::vector<double>& mark_a,
                    const std::vector<double>& mark_b, const std::vector<TestNoise>& noise) {
  Separation s;
  s.a = std::move(a);
  s.b = std::move(b);
  // The best test: the most discriminating of those whose marks part beyond budget + lab
  // uncertainty (visible), else the most discriminating, not visible; so "no test shows it" is
  // said only when none does.
  for (std::size_t k = 0; k < noise.size(); ++k) {
    const double apart =
        std::abs((mark_a.empty() ? 0.0 : mark_a[k]) - (mark_b.empty() ? 0.0 : mark_b[k]));
    const double d = apart / noise[k].total();
    s.discrimination.push_back(std::isfinite(d) ? d : std::numeric_limits<double>::quiet_NaN());
    if (!std::isfinite(d)) continue;
    const bool visible = apart > noise[k].budget + noise[k].sigma;
    if (!s.best || (visible && !s.visible) ||
        (visible == s.visible && d > s.discrimination[*s.best])) {
      s.best = k;
      s.visible = visible;
    }
  }
  return s;
}

std::vector<double> joined_marks(const std::vector<double>& change,
                                 const std::vector<std::array<double, 2>>& jacobian,
                                 const std::vector<double>& weight,
                                 const std::vector<Target>& targets, std::size_t n) {
  std::vector<double> out;
  for (std::size_t k = n; k < targets.size(); ++k) {
    std::vector<double> joined = weight;
    joined[k] = refit_weight(targets[k]);
    out.push_back(change_after_refit(change, jacobian, joined)[k]);
  }
  return out;
}

std::size_t run_of(const NextTest& next, const std::string& effect) {
  for (std::size_t e = 0; e < next.effects.size() && !effect.empty(); ++e) {
    if (next.effects[e] == effect) return kNextTestBaseRuns + e;
  }
  return 0;
}

std::vector<double> mark_of(const NextTest& next, const std::string& effect) {
  if (effect.empty()) return std::vector<double>(next.menu.size(), 0.0);
  for (std::size_t e = 0; e < next.effects.size(); ++e) {
    if (next.effects[e] == effect) return next.mark[e];
  }
  return {};
}

}  // namespace rockcal::diagnosis
