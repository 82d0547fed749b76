#include "orchestrator/calibration/bayes/box.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rockcal::calibration {
namespace {

double unit(double v, const Range& r) {
  return std::clamp(std::log(v / r.lo) / std::log(r.hi / r.lo), 0.0, 1.0);
}

}  // namespace

Eigen::Vector2d to_unit(const BondPoint& p, const CalibrationCampaign& c) {
  return {unit(p.fr0_n, c.fr0_n), unit(p.fs0_n, c.fs0_n)};
}

double strength_at(double u, int which, const CalibrationCampaign& c) {
  const Range& r = which == 0 ? c.fr0_n : c.fs0_n;
  return r.lo * std::pow(r.hi / r.lo, std::clamp(u, 0.0, 1.0));
}

std::string bound_text(int which, bool upper, const Range& r) {
  char text[128];
  std::snprintf(text, sizeof text, "the %s bound of %s (%.4g)", upper ? "upper" : "lower",
                which == 0 ? "F_r0" : "F_s0", upper ? r.hi : r.lo);
  return text;
}

BondPoint from_unit(const Eigen::Vector2d& x, const CalibrationCampaign& c) {
  return {strength_at(x(0), 0, c), strength_at(x(1), 1, c)};
}

}  // namespace rockcal::calibration
