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

bool HomogeneityChecks::holds() const {
  bool any = false;
  for (const Homogeneity& h : checks) {
    if (!h.measured) continue;
    if (!h.holds) return false;
    any = true;
  }
  return any;
}

double HomogeneityChecks::degree() const {
  double sum = 0.0;
  int n = 0;
  for (const Homogeneity& h : checks) {
    if (h.measured) sum += h.degree(), ++n;
  }
  return n ? sum / n : 1.0;
}

double probe_scale_factor(const BondPoint& base, const CalibrationCampaign& c) {
  const double room_up = std::min(c.fr0_n.hi / base.fr0_n, c.fs0_n.hi / base.fs0_n);
  if (room_up >= 2.0) return 2.0;
  const double room_down = std::min(base.fr0_n / c.fr0_n.lo, base.fs0_n / c.fs0_n.lo);
  if (room_up >= room_down) return room_up;
  return 1.0 / std::min(2.0, room_down);
}

double probe_toward_targets(const EvaluationRecord& base, const CalibrationCampaign& c) {
  const PeakLoads& t = c.targets.model_loads_n;
  const double mean_log_error = (c.weight_uct * std::log(base.loads->uct_n / t.uct_n) +
                                 c.weight_btt * std::log(base.loads->btt_n / t.btt_n)) /
                                (c.weight_uct + c.weight_btt);
  // Degree 1 guess of the scale that meets the targets, kept between 1.5x and 2x either way.
  const double wanted = std::clamp(std::abs(mean_log_error), std::log(1.5), std::log(2.0));
  const double room_up = std::min(c.fr0_n.hi / base.point.fr0_n, c.fs0_n.hi / base.point.fs0_n);
  const double room_down = std::min(base.point.fr0_n / c.fr0_n.lo, base.point.fs0_n / c.fs0_n.lo);
  const double up = std::min(std::exp(wanted), room_up);
  const double down = std::min(std::exp(wanted), room_down);
  const bool prefer_up = mean_log_error <= 0;
  if (prefer_up && up >= kMinCheckScale) return up;
  if (!prefer_up && down >= kMinCheckScale) return 1.0 / down;
  if (up >= kMinCheckScale) return up;
  if (down >= kMinCheckScale) return 1.0 / down;
  return 1.0;
}

}  // namespace rockcal::calibration
