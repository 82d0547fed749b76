#include "orchestrator/calibration/homogeneity.hpp"

#include <algorithm>
#include <cmath>

namespace rockcal::calibration {

Homogeneity measure_homogeneity(const EvaluationRecord& base, const EvaluationRecord& scaled,
                                double tolerance) {
  Homogeneity h;
  h.base = base.point;
  h.scale_factor = scaled.point.fr0_n / base.point.fr0_n;
  if (!base.loads || !scaled.loads || std::abs(std::log(h.scale_factor)) < 1e-6) return h;
  const double log_c = std::log(h.scale_factor);
  h.measured = true;
  h.exponent_uct = std::log(scaled.loads->uct_n / base.loads->uct_n) / log_c;
  h.exponent_btt = std::log(scaled.loads->btt_n / base.loads->btt_n) / log_c;
  h.holds = std::abs(h.exponent_uct - h.exponent_btt) <= tolerance && h.degree() >= 0.5 &&
            h.degree() <= 2.0;
  return h;
}

double probe_scale_factor(const BondPoint& base, const CalibrationCampaign& c) {
  const double room_up = std::min(c.fr0_n.hi / base.fr0_n, c.fs0_n.hi / base.fs0_n);
  if (room_up >= 2.0) return 2.0;
  const double room_down = std::min(base.fr0_n / c.fr0_n.lo, base.fs0_n / c.fs0_n.lo);
  if (room_up >= room_down) return room_up;
  return 1.0 / std::min(2.0, room_down);
}

}  // namespace rockcal::calibration
