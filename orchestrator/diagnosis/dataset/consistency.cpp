#include "orchestrator/diagnosis/dataset/consistency.hpp"

#include <cmath>
#include <cstdio>
#include <optional>

namespace rockcal::diagnosis {
namespace {

bool close(double a, double b) {
  return std::abs(a - b) <= 0.01 * std::max(std::abs(a), std::abs(b));
}

bool close(const std::optional<double>& a, const std::optional<double>& b) {
  if (!a || !b) return !a && !b;
  return close(*a, *b);
}

bool same_conditions(const Observation& a, const Observation& b) {
  return a.test == b.test && a.observable == b.observable &&
         close(a.conditions.diameter_m, b.conditions.diameter_m) &&
         close(a.conditions.height_m, b.conditions.height_m) &&
         close(a.conditions.thickness_m, b.conditions.thickness_m) &&
         close(a.conditions.confining_pressure_pa, b.conditions.confining_pressure_pa) &&
         close(a.conditions.loading_rate_m_s, b.conditions.loading_rate_m_s);
}

}  // namespace

std::vector<Inconsistency> find_inconsistencies(const Dataset& d, double z) {
  std::vector<Inconsistency> out;
  const std::vector<Observation>& o = d.observations;
  for (std::size_t i = 0; i < o.size(); ++i) {
    for (std::size_t j = i + 1; j < o.size(); ++j) {
      if (!same_conditions(o[i], o[j]) || !(o[i].value > 0) || !(o[j].value > 0)) continue;
      const double diff = std::log(o[j].value / o[i].value);
      const double sd = std::hypot(o[i].uncertainty / o[i].value, o[j].uncertainty / o[j].value);
      if (std::abs(diff) > z * sd) out.push_back({o[i].id, o[j].id, diff, std::abs(diff) / sd});
    }
  }
  return out;
}

std::string inconsistency_text(const std::vector<Inconsistency>& pairs) {
  std::string out;
  for (const Inconsistency& p : pairs) {
    char line[256];
    std::snprintf(line, sizeof line, "%s and %s (the same test) differ by %+.3g%% (%.2g sd)",
                  p.first.c_str(), p.second.c_str(), 100 * std::expm1(p.ln_difference), p.sigmas);
    out += (out.empty() ? "" : "; ") + std::string(line);
  }
  return out;
}

}  // namespace rockcal::diagnosis
