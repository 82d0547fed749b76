#include "orchestrator/calibration/local_search.hpp"

#include <cmath>
#include <limits>

#include "orchestrator/calibration/algorithms.hpp"
#include "orchestrator/calibration/nlopt_bridge.hpp"
#include "orchestrator/calibration/search_space.hpp"

namespace rockcal::calibration {

void local_search(Ledger& ledger, const CalibrationCampaign& campaign, const BondPoint& start,
                  double initial_step) {
  const LogBox box = log_box(campaign);
  const double du = box.u.hi - box.u.lo;
  const double dv = box.v.hi - box.v.lo;
  nlopt::opt opt(*nlopt_algorithm(campaign.algorithm), 2);
  opt.set_lower_bounds({0.0, 0.0});
  opt.set_upper_bounds({1.0, 1.0});
  opt.set_initial_step(std::vector<double>{initial_step, initial_step});
  opt.set_xtol_abs(1e-4);
  opt.set_ftol_rel(1e-4);  // a compromise has a floor; do not crawl along it
  opt.set_maxeval(10 * campaign.max_evaluations);  // the ledger's budget ends it first
  std::vector<double> z = {clamp_to((std::log(start.fr0_n) - box.u.lo) / du, {0, 1}),
                           clamp_to((std::log(start.fs0_n) - box.v.lo) / dv, {0, 1})};
  minimise(opt, z, [&](const std::vector<double>& x) {
    const BondPoint p = point_from_logs(box.u.lo + x[0] * du, box.v.lo + x[1] * dv);
    return ledger.evaluate_one(p, "local").misfit;
  });
}

void local_search_with_restarts(Ledger& ledger, const CalibrationCampaign& campaign,
                                const BondPoint& start) {
  constexpr int kRuns = 5;
  BondPoint from = start;
  double step = 0.1;
  double best_misfit = std::numeric_limits<double>::infinity();
  for (int run = 0; run < kRuns; ++run, step *= 0.5) {
    local_search(ledger, campaign, from, step);
    const EvaluationRecord* best = ledger.best();
    if (!best || !(best->misfit < best_misfit)) return;
    best_misfit = best->misfit;
    from = best->point;
  }
}

}  // namespace rockcal::calibration
