// The calibration's parameters in the inference core's coordinates: (ln F_r0, ln F_s0) mapped
// linearly onto the unit square by the campaign's bounds (a log-uniform prior on each strength).
#pragma once

#include <string>

#include <Eigen/Dense>

#include "orchestrator/calibration/campaign.hpp"

namespace rockcal::calibration {

Eigen::Vector2d to_unit(const BondPoint& p, const CalibrationCampaign& c);
BondPoint from_unit(const Eigen::Vector2d& x, const CalibrationCampaign& c);
// A unit coordinate of one strength back to model units (`which`: 0 F_r0, 1 F_s0).
double strength_at(double u, int which, const CalibrationCampaign& c);
// A bound as reports word it: "the upper bound of F_r0 (1000)" (`which`: 0 F_r0, 1 F_s0; `r` the
// strength's bounds).
std::string bound_text(int which, bool upper, const Range& r);

}  // namespace rockcal::calibration
