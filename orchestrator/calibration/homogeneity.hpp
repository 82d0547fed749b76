// The structural check behind ratio-then-scale. For a quasi-static brittle bond model, scaling
// F_r0 and F_s0 by c scales both peak loads by c (the bond forces at breakage scale with the
// strengths, the stiffnesses do not change, so the displacement field at failure scales by c too);
// then the UCT/BTT ratio depends on F_s0/F_r0 alone. Inertia, friction and damping break this, so
// it is measured: a point and its scaled copy give the exponents p = ln(L(c x)/L(x)) / ln c.
#pragma once

#include <limits>
#include <vector>

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

// All checks of a campaign. The structure is exploited only while every measured check holds: a
// model with a force scale of its own (a frictional floor under weak bonds, say) can look
// homogeneous at one place and not at another.
struct HomogeneityChecks {
  std::vector<Homogeneity> checks;
  bool holds() const;     // at least one check measured, and every measured one holds
  double degree() const;  // mean degree of the measured checks, 1 without any
};

// `tolerance` bounds |p_uct - p_btt| (the ratio's drift per e-fold of scale); the common degree
// must also be clearly positive so that a scale step has a direction.
Homogeneity measure_homogeneity(const EvaluationRecord& base, const EvaluationRecord& scaled,
                                double tolerance);

// The probe partner of `base`: 2x when it fits in the bounds, else as large as fits, else halved.
double probe_scale_factor(const BondPoint& base, const CalibrationCampaign& campaign);
// The probe partner of an evaluated point, scaled toward the targets (1.5x to 2x, or down), so the
// check also moves the search closer; 1 when the bounds leave no room.
double probe_toward_targets(const EvaluationRecord& base, const CalibrationCampaign& campaign);

// Pairs closer than this in scale measure noise rather than an exponent.
inline constexpr double kMinCheckScale = 1.25;

}  // namespace rockcal::calibration
