// The structural check behind ratio-then-scale. For a quasi-static brittle bond model, scaling
// F_r0 and F_s0 by c scales both peak loads by c (the bond forces at breakage scale with the
// strengths, the stiffnesses do not change, so the displacement field at failure scales by c too);
// then the UCT/BTT ratio depends on F_s0/F_r0 alone. Inertia, friction and damping break this, so
// it is measured: a point and its scaled copy give the exponents p = ln(L(c x)/L(x)) / ln c.
#pragma once

#include <limits>

#include "orchestrator/calibration/ledger.hpp"

namespace rockcal::calibration {

struct Homogeneity {
  bool measured = false;  // both probe runs succeeded
  BondPoint base{};
  double scale_factor = 0.0;  // c of the probe pair
  double exponent_uct = std::numeric_limits<double>::quiet_NaN();
  double exponent_btt = std::numeric_limits<double>::quiet_NaN();
  bool holds = false;  // the ratio is scale-invariant enough to search it in 1-D
  double degree() const { return 0.5 * (exponent_uct + exponent_btt); }
};

// `tolerance` bounds |p_uct - p_btt| (the ratio's drift per e-fold of scale); the common degree
// must also be clearly positive so that a scale step has a direction.
Homogeneity measure_homogeneity(const EvaluationRecord& base, const EvaluationRecord& scaled,
                                double tolerance);

// The probe partner of `base`: 2x when it fits in the bounds, else as large as fits, else halved.
double probe_scale_factor(const BondPoint& base, const CalibrationCampaign& campaign);

}  // namespace rockcal::calibration
