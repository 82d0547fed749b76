#include "engine/run_cost.hpp"

#include "engine/loadtests/loading_speed.hpp"

#include <algorithm>
#include <cmath>

#include "engine/loadtests/driver.hpp"
#include "engine/loadtests/specimen.hpp"
#include "engine/spec.hpp"
#include "engine/units.hpp"

namespace rockcal {
namespace {

// Ramps (approach, loading, slow-down: at most 3, each max(ramp_fraction x the loading time, 2
// transits)), the seating hold (1 transit) and a triaxial confinement (4 transits x max(1, D/H)):
// compression.cpp's phases besides the platen travel, in transits.
constexpr double kRamps = 3.0;
constexpr double kRampTransits = 2.0;
constexpr double kOtherTransits = 5.0;

}  // namespace

double run_time_step(const JobSpec& run) {
  if (run.loading.dt_s) return *run.loading.dt_s;
  // A random packing's smallest grain (radius / radius_ratio at least) sets the step.
  return run.loading.dt_safety * critical_time_step(run) / run.sample.radius_ratio;
}

double wave_speed(const JobSpec& run) {
  return loaded_length(run) / wave_transit_time(run);
}

double estimated_steps(const JobSpec& run) {
  const LoadingSpec& l = run.loading;
  const double dt = run_time_step(run);
  const double transit = wave_transit_time(run);
  const double cap = l.max_steps ? static_cast<double>(*l.max_steps) : INFINITY;
  if (run.test == TestKind::elastic) {
    const double stages = 2.0 * (kElasticLoadTransits + kElasticHoldLimitTransits) * transit / dt;
    return std::min(stages, cap);
  }
  const double aspect = std::max(1.0, run.sample.diameter_m / run.sample.height_m);
  auto steps_at = [&](double speed) {
    const double travel = l.max_strain * loaded_length(run) / (2.0 * speed);
    const double ramp = std::max(l.ramp_fraction * travel, kRampTransits * transit);
    const double seconds =
        travel / l.slow_factor + kRamps * ramp + kOtherTransits * aspect * transit;
    return std::min(seconds / dt, cap);
  };
  // "auto": the bond-controlled window at the rock's own speed, then (speed_up_past_window) the
  // rest of max_strain at the late speed (loadtests/loading_speed.hpp); a given speed throughout.
  const bool stops_at_window = !l.platen_velocity_m_s && !l.speed_up_past_window;
  const double speed = l.platen_velocity_m_s ? *l.platen_velocity_m_s : late_platen_speed(run);
  double steps =
      stops_at_window
          ? std::min((kRamps * kRampTransits + kOtherTransits * aspect) * transit / dt, cap)
          : steps_at(speed);
  if (!l.platen_velocity_m_s) {
    steps +=
        std::min(kBondControlledWindow * l.auto_transits * transit / (l.slow_factor * dt), cap);
  }
  // A rate study's runs after the probe: at halving speeds from half the job's (or slower).
  if (l.rate_study) {
    for (std::int64_t k = 1; k <= l.rate_study_runs; ++k)
      steps += steps_at(platen_speed(run) / std::ldexp(1.0, static_cast<int>(k)));
  }
  return std::isnan(steps) ? INFINITY : steps;
}

}  // namespace rockcal
