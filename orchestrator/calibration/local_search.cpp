#include "orchestrator/calibration/local_search.hpp"

#include <cmath>

#include "orchestrator/calibration/algorithms.hpp"
#include "orchestrator/calibration/nlopt_bridge.hpp"
#include "orchestrator/calibration/search_space.hpp"

namespace rockcal::calibration {

void local_search(Ledger& ledger, const CalibrationCampaign& campaign, const BondPoint& start) {
  const LogBox box = log_box(campaign);
  const double du = box.u.hi - box.u.lo;
  const double dv = box.v.hi - box.v.lo;
  nlopt::opt opt(*nlopt_algorithm(campaign.algorithm), 2);
  opt.set_lower_bounds({0.0, 0.0});
  opt.set_upper_bounds({1.0, 1.0});
  opt.set_initial_step(std::vector<double>{0.1, 0.1});
  opt.set_xtol_abs(1e-4);
  opt.set_maxeval(10 * campaign.max_evaluations);  // the ledger's budget ends it first
  std::vector<double> z = {clamp_to((std::log(start.fr0_n) - box.u.lo) / du, {0, 1}),
                           clamp_to((std::log(start.fs0_n) - box.v.lo) / dv, {0, 1})};
  minimise(opt, z, [&](const std::vector<double>& x) {
    const BondPoint p = point_from_logs(box.u.lo + x[0] * du, box.v.lo + x[1] * dv);
    return ledger.evaluate_one(p, "local").misfit;
  });
}

}  // namespace rockcal::calibration
