// The search space: F_r0 and F_s0 in log space within their bounds, and the "ratio coordinates"
// s = ln(F_s0 / F_r0) (which, for a homogeneous model, alone sets the UCT/BTT load ratio) and
// m = (ln F_r0 + ln F_s0) / 2 (the log scale; scaling both strengths by c adds ln c to m).
#pragma once

#include "orchestrator/calibration/campaign.hpp"
#include "orchestrator/calibration/evaluator.hpp"

namespace rockcal::calibration {

struct LogBox {
  Range u;  // ln F_r0
  Range v;  // ln F_s0
};

struct RatioCoords {
  double s;  // ln(F_s0 / F_r0)
  double m;  // mean log strength
};

LogBox log_box(const CalibrationCampaign& campaign);
BondPoint point_from_logs(double u, double v);
// Clips into the bounds: NLopt (BOBYQA) may step a rounding error outside, and exp(log(x)) may
// round past a bound; the job must stay inside what the user allowed.
BondPoint clip_to_bounds(const BondPoint& point, const CalibrationCampaign& campaign);

RatioCoords ratio_coords(const BondPoint& point);
BondPoint point_from_ratio_coords(const RatioCoords& coords);
// The s over which some point of the box exists, and the m range of the box at a given s.
Range s_range(const LogBox& box);
Range m_range(const LogBox& box, double s);

double clamp_to(double x, const Range& range);

}  // namespace rockcal::calibration
