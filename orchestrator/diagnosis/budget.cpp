#include "orchestrator/diagnosis/budget.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rockcal::diagnosis {

std::vector<BudgetVariant> budget_variants(const BudgetSpec& spec, std::uint64_t template_seed) {
  std::vector<BudgetVariant> out;
  for (std::uint64_t seed : spec.seeds) {
    out.push_back({"seed " + std::to_string(seed), {seed, 1.0, 1.0}});
  }
  auto factor = [](double x) {
    std::string s = std::to_string(x);
    s.erase(s.find_last_not_of('0') + 1);
    if (s.back() == '.') s.pop_back();
    return s;
  };
  out.push_back({"speed x" + factor(spec.speed_factor), {template_seed, spec.speed_factor, 1.0}});
  out.push_back({"resolution x" + factor(spec.resolution), {template_seed, 1.0, spec.resolution}});
  return out;
}

Budget numerical_budget(std::vector<BudgetVariant> variants, const RunOutcome& reference,
                        const std::vector<RunOutcome>& outcomes) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::size_t n = reference.values.size();
  Budget b;
  b.variants = std::move(variants);
  b.per_target.assign(n, 0.0);
  b.measured.assign(n, false);
  for (const RunOutcome& o : outcomes) {
    std::vector<double> change(n, nan);
    for (std::size_t i = 0; i < n; ++i) {
      if (reference.values[i] && o.values[i]) {
        change[i] = std::abs(std::log(*o.values[i] / *reference.values[i]));
        b.per_target[i] = std::max(b.per_target[i], change[i]);
        b.measured[i] = true;
      }
    }
    b.change.push_back(std::move(change));
  }
  double largest = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (b.measured[i]) largest = std::max(largest, b.per_target[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!b.measured[i]) b.per_target[i] = largest;
  }
  return b;
}

}  // namespace rockcal::diagnosis
