// The space-filling start, evaluated as one concurrent batch: the centre of the log box, its scaled
// copy (the homogeneity probe), and a Latin hypercube of `initial_points` points.
#pragma once

#include <vector>

#include "orchestrator/calibration/campaign.hpp"
#include "orchestrator/calibration/evaluator.hpp"

namespace rockcal::calibration {

// [0] = centre, [1] = probe partner of the centre, [2..] = Latin hypercube.
std::vector<BondPoint> start_design(const CalibrationCampaign& campaign);

}  // namespace rockcal::calibration
