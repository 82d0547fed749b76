#include "orchestrator/diagnosis/analysis/consistency.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rockcal::diagnosis {
namespace {

bool within(double a, double b, double tolerance) {
  return std::abs(a - b) <= tolerance * std::max(std::abs(a), std::abs(b));
}

}  // namespace

bool same_conditions(const Target& a, const Target& b) {
  const RunConditions& x = a.conditions;
  const RunConditions& y = b.conditions;
  if (x.test != y.test || a.observable != b.observable) return false;
  const double size =
      a.observable == Observable::peak_load ? kSameSizeForLoads : kSameSizeForIntensive;
  const bool disc = x.test == TestKind::btt;
  return within(x.diameter_m, y.diameter_m, size) &&
         (disc ? within(x.thickness_m, y.thickness_m, size)
               : within(x.height_m, y.height_m, size)) &&
         within(x.confining_pressure_pa, y.confining_pressure_pa, kSameLoading) &&
         within(x.platen_velocity_m_s, y.platen_velocity_m_s, kSameLoading);
}

std::vector<Inconsistency> find_inconsistencies(const std::vector<Target>& t) {
  std::vector<Inconsistency> out;
  for (std::size_t i = 0; i < t.size(); ++i) {
    for (std::size_t j = i + 1; j < t.size(); ++j) {
      if (!same_conditions(t[i], t[j]) || !(t[i].value > 0) || !(t[j].value > 0)) continue;
      const double diff = std::log(t[j].value / t[i].value);
      const double sd = std::hypot(t[i].sigma, t[j].sigma);
      if (std::abs(diff) > kDisagreementSd * sd) out.push_back({i, j, diff, std::abs(diff) / sd});
    }
  }
  return out;
}

std::vector<DataSpan> data_spans(const std::vector<Target>& targets) {
  std::vector<DataSpan> out(targets.size());
  for (const Inconsistency& p : find_inconsistencies(targets)) {
    DataSpan& a = out[p.first];
    DataSpan& b = out[p.second];
    a.lo = std::min(a.lo, p.ln_difference);
    a.hi = std::max(a.hi, p.ln_difference);
    b.lo = std::min(b.lo, -p.ln_difference);
    b.hi = std::max(b.hi, -p.ln_difference);
  }
  return out;
}

std::string inconsistency_text(const std::vector<Inconsistency>& pairs,
                               const std::vector<Target>& targets) {
  std::string out;
  for (const Inconsistency& p : pairs) {
    const Target& a = targets[p.first];
    char line[384];
    std::snprintf(line, sizeof line,
                  "%s and %s (%s %s, nearly the same conditions) differ by %+.3g%% in value, "
                  "%.1f times their combined uncertainty",
                  a.id.c_str(), targets[p.second].id.c_str(), to_string(a.conditions.test),
                  to_string(a.observable), 100 * std::expm1(p.ln_difference), p.sigmas);
    out += (out.empty() ? "" : "; ") + std::string(line);
  }
  return out;
}

}  // namespace rockcal::diagnosis
