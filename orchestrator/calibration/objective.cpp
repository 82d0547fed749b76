#include "orchestrator/calibration/objective.hpp"

#include <cmath>

namespace rockcal::calibration {

LogErrors log_errors(const PeakLoads& sim, const PeakLoads& target) {
  return {std::log(sim.uct_n / target.uct_n), std::log(sim.btt_n / target.btt_n)};
}

double misfit(const LogErrors& e, const Weights& w) {
  return w.uct * e.uct * e.uct + w.btt * e.btt * e.btt;
}

double relative_error(double simulated, double target) {
  return simulated / target - 1.0;
}

bool within_tolerance(const PeakLoads& sim, const PeakLoads& target, double tolerance,
                      const PeakLoads& rel_se) {
  return std::abs(relative_error(sim.uct_n, target.uct_n)) <= tolerance + rel_se.uct_n &&
         std::abs(relative_error(sim.btt_n, target.btt_n)) <= tolerance + rel_se.btt_n;
}

double scale_shift(const LogErrors& e, const Weights& w, double degree) {
  return -(w.uct * e.uct + w.btt * e.btt) / ((w.uct + w.btt) * degree);
}

}  // namespace rockcal::calibration
