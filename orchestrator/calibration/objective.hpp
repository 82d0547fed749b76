// The misfit of one evaluation: weighted squared log-ratios of simulated to target peak loads.
// Log-ratios make a factor 2 too high cost as much as a factor 2 too low, and make the misfit of a
// load that scales like c^p quadratic in ln c (which the ratio-then-scale step relies on).
#pragma once

#include "orchestrator/calibration/evaluator.hpp"

namespace rockcal::calibration {

struct Weights {
  double uct;
  double btt;
};

// ln(simulated / target) per test.
struct LogErrors {
  double uct;
  double btt;
};

LogErrors log_errors(const PeakLoads& simulated_n, const PeakLoads& target_n);
double misfit(const LogErrors& errors, const Weights& weights);
// Both loads within the relative tolerance of their targets. An ensemble mean is only known to its
// standard error, so each load's band is widened by its relative standard error (`rel_se`, se /
// mean; zero for a single run): a mean one standard error outside the tolerance is not evidence
// that the point misses.
bool within_tolerance(const PeakLoads& simulated_n, const PeakLoads& target_n, double tolerance,
                      const PeakLoads& rel_se = {0.0, 0.0});
// The log-scale shift that minimises the misfit along a ray of scaled strengths, when both loads
// scale like c^degree: degree * shift = -(w_u e_u + w_b e_b) / (w_u + w_b).
double scale_shift(const LogErrors& errors, const Weights& weights, double degree);
double relative_error(double simulated, double target);

}  // namespace rockcal::calibration
