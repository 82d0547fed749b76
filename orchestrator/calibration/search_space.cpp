#include "orchestrator/calibration/search_space.hpp"

#include <algorithm>
#include <cmath>

namespace rockcal::calibration {

LogBox log_box(const CalibrationCampaign& c) {
  return {{std::log(c.fr0_n.lo), std::log(c.fr0_n.hi)},
          {std::log(c.fs0_n.lo), std::log(c.fs0_n.hi)}};
}

BondPoint point_from_logs(double u, double v) {
  return {std::exp(u), std::exp(v)};
}

double clamp_to(double x, const Range& range) {
  return std::clamp(x, range.lo, range.hi);
}

BondPoint clip_to_bounds(const BondPoint& p, const CalibrationCampaign& c) {
  return {clamp_to(p.fr0_n, c.fr0_n), clamp_to(p.fs0_n, c.fs0_n)};
}

RatioCoords ratio_coords(const BondPoint& p) {
  const double u = std::log(p.fr0_n);
  const double v = std::log(p.fs0_n);
  return {v - u, 0.5 * (u + v)};
}

BondPoint point_from_ratio_coords(const RatioCoords& r) {
  return point_from_logs(r.m - 0.5 * r.s, r.m + 0.5 * r.s);
}

Range s_range(const LogBox& b) {
  return {b.v.lo - b.u.hi, b.v.hi - b.u.lo};
}

// u = m - s/2 and v = m + s/2 must both lie in their ranges.
Range m_range(const LogBox& b, double s) {
  const double lo = std::max(b.u.lo + 0.5 * s, b.v.lo - 0.5 * s);
  const double hi = std::min(b.u.hi + 0.5 * s, b.v.hi - 0.5 * s);
  return {lo, std::max(lo, hi)};
}

}  // namespace rockcal::calibration
