#include "orchestrator/diagnosis/analysis/trust_region.hpp"

#include <algorithm>
#include <cmath>

namespace rockcal::diagnosis {

namespace {

double distance(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) d = std::max(d, std::abs(a[k] - b[k]));
  return d;
}

}  // namespace

void TrustRegion::start_from(const std::vector<double>& z, double misfit,
                             const std::vector<double>& ln) {
  if (!best_ln.empty() && !(misfit < best)) return;
  best = misfit;
  best_z = z;
  best_ln = ln;
}

bool TrustRegion::record(const std::vector<double>& z, double misfit,
                         const std::vector<double>& ln) {
  if (best_ln.empty() || misfit < best) {
    start_from(z, misfit, ln);
    return true;
  }
  radius = 0.5 * distance(z, best_z);
  return false;
}

std::optional<std::vector<double>> TrustRegion::next(const std::vector<double>& target,
                                                     double settled) {
  if (radius < settled) return std::nullopt;
  const double moved = distance(target, best_z);
  if (moved < settled) return std::nullopt;
  const double damp = std::min(1.0, radius / moved);
  std::vector<double> z(target.size());
  for (std::size_t d = 0; d < z.size(); ++d) z[d] = best_z[d] + damp * (target[d] - best_z[d]);
  return z;
}

}  // namespace rockcal::diagnosis
