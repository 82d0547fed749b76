#include "orchestrator/calibration/start_design.hpp"

#include "orchestrator/calibration/homogeneity.hpp"
#include "orchestrator/calibration/latin_hypercube.hpp"
#include "orchestrator/calibration/search_space.hpp"

namespace rockcal::calibration {

std::vector<BondPoint> start_design(const CalibrationCampaign& c) {
  const LogBox box = log_box(c);
  const BondPoint centre =
      point_from_logs(0.5 * (box.u.lo + box.u.hi), 0.5 * (box.v.lo + box.v.hi));
  const double factor = probe_scale_factor(centre, c);
  std::vector<BondPoint> points = {centre, {centre.fr0_n * factor, centre.fs0_n * factor}};
  for (const auto& z : latin_hypercube(c.initial_points, c.random_seed)) {
    points.push_back(point_from_logs(box.u.lo + z[0] * (box.u.hi - box.u.lo),
                                     box.v.lo + z[1] * (box.v.hi - box.v.lo)));
  }
  return points;
}

}  // namespace rockcal::calibration
