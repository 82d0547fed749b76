#include "orchestrator/diagnosis/analysis/trust_region.hpp"

#include <algorithm>
#include <cmath>

namespace rockcal::diagnosis {

bool TrustRegion::record(const std::vector<double>& z, double misfit,
                         const std::vector<double>& ln) {
  if (best_ln.empty() || misfit < best) {
    best = misfit;
    best_z = z;
    best_ln = ln;
    return true;
  }
  radius = 0.5 * step;
  return false;
}

std::optional<std::vector<double>> TrustRegion::next(const std::vector<double>& target,
                                                     double settled) {
  if (radius < settled) return std::nullopt;
  double moved = 0.0;
  for (std::size_t d = 0; d < target.size(); ++d)
    moved = std::max(moved, std::abs(target[d] - best_z[d]));
  if (moved < settled) return std::nullopt;
  const double damp = std::min(1.0, radius / moved);
  std::vector<double> z(target.size());
  for (std::size_t d = 0; d < z.size(); ++d) z[d] = best_z[d] + damp * (target[d] - best_z[d]);
  step = damp * moved;
  return z;
}

}  // namespace rockcal::diagnosis
