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

ModulusWindow modulus_window(const std::vector<CurvePoint>& curve, double base_load,
                             double peak_load) {
  const double reference = first_failure_load(curve, base_load, peak_load);
  ModulusWindow w{base_load, kModulusLow * reference, kModulusHigh * reference, curve.size()};
  for (std::size_t row = 0; row < curve.size(); ++row) {
    if (curve[row].load_n - base_load >= reference) {
      w.end = row;
      break;
    }
  }
  return w;
}

void LineFit::add(double x, double y) {
  sx += x;
  sy += y;
  sxx += x * x;
  sxy += x * y;
  ++n;
}

std::optional<double> LineFit::slope() const {
  const double den = n * sxx - sx * sx;
  if (n < 3 || den <= 0) return std::nullopt;
  return (n * sxy - sx * sy) / den;
}

std::optional<double> prepeak_modulus(const std::vector<CurvePoint>& curve, double base_load,
                                      double peak_load, double area_m2, double length_m) {
  const ModulusWindow window = modulus_window(curve, base_load, peak_load);
  LineFit fit;
  for (std::size_t row = 0; row < window.end; ++row) {
    if (window.contains(curve, row))
      fit.add(curve[row].displacement_m / length_m, (curve[row].load_n - base_load) / area_m2);
  }
  return fit.slope();
}

}  // namespace rockcal
