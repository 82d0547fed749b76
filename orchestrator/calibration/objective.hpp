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
// Both loads within the relative tolerance of their targets.
bool within_tolerance(const PeakLoads& simulated_n, const PeakLoads& target_n, double tolerance);
double relative_error(double simulated, double target);

}  // namespace rockcal::calibration
