#include "engine/loadtests/modulus.hpp"

#include <algorithm>

namespace rockcal {

double first_failure_load(const std::vector<CurvePoint>& curve, double base_load,
                          double peak_load) {
  const double peak = peak_load - base_load;
  double running_max = 0.0;
  for (const CurvePoint& point : curve) {
    const double load = point.load_n - base_load;
    running_max = std::max(running_max, load);
    if (point.broken_bonds > 0 && load < (1.0 - kFailureDrop) * running_max) {
      return std::min(running_max, peak);
    }
  }
  return peak;
}

std::optional<double> prepeak_modulus(const std::vector<CurvePoint>& curve, double base_load,
                                      double peak_load, double area_m2, double length_m) {
  const double reference = first_failure_load(curve, base_load, peak_load);
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (const CurvePoint& point : curve) {
    const double load = point.load_n - base_load;
    if (load >= reference) break;
    if (load < kModulusLow * reference || load > kModulusHigh * reference) continue;
    const double x = point.displacement_m / length_m, y = load / area_m2;
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    ++n;
  }
  const double den = n * sxx - sx * sx;
  if (n < 3 || den <= 0) return std::nullopt;
  return (n * sxy - sx * sy) / den;
}

}  // namespace rockcal
