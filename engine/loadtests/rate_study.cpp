#include <algorithm>
#include <cmath>

#include "engine/effects/effect.hpp"
#include "engine/loadtests/driver.hpp"
#include "engine/loadtests/loading_speed.hpp"
#include "engine/loadtests/specimen.hpp"

namespace rockcal {
namespace {

// The first speed of the study gives the specimen this many elastic-wave transit times to reach its
// peak: slower than that, a bonded specimen is close to quasi-static (field notes; ESys-Particle's
// peak still moved 2-4.5% per halving below it, hence the extrapolation).
constexpr double kTransitsToPeak = 20.0;

// Peak at zero speed: if the last two differences shrink by a ratio q in (0, 1), the remaining ones
// form a geometric series: P0 = P_n + d_n q / (1 - q). Otherwise the last difference is the error
// estimate, and the sequence counts as converged only when both last differences are below kSettled
// of the peak (they are then round-off-level noise).
constexpr double kSettled = 0.005;

}  // namespace

void extrapolate_to_zero_speed(RateStudy& s) {
  const std::size_t n = s.peaks_n.size();
  const double last = s.peaks_n[n - 1];
  const double d_last = last - s.peaks_n[n - 2];
  const double d_prev = n >= 3 ? s.peaks_n[n - 2] - s.peaks_n[n - 3] : d_last;
  const double q = d_prev != 0.0 ? d_last / d_prev : 0.0;
  if (n >= 3 && q > 0.0 && q < 1.0) {
    s.extrapolated_peak_n = last + d_last * q / (1.0 - q);
    s.rate_error = std::abs(last - s.extrapolated_peak_n) / std::abs(s.extrapolated_peak_n);
    s.converged = true;
    return;
  }
  s.extrapolated_peak_n = last;
  s.rate_error = std::abs(d_last) / std::abs(last);
  s.converged = std::max(std::abs(d_last), std::abs(d_prev)) < kSettled * std::abs(last);
}

TestResult run_rate_study(const JobSpec& job, const RunHooks& hooks) {
  const JobSpec spec = effective_spec(job);  // the speeds below are the ones the runs use
  JobSpec run = spec;
  run.loading.rate_study = false;
  // A probe at the job's own speed tells the strain at peak, which sets the starting speed.
  TestResult probe = run_compression_test(run, hooks);
  // A run without a peak has nothing to extrapolate: the study ends with that run's reason.
  auto no_peak = [](TestResult r, double v) {
    r.no_peak_reason =
        "rate study run at platen speed " + nlohmann::json(v).dump() + " m/s: " + r.no_peak_reason;
    return r;
  };
  const double probe_speed = platen_speed(spec);
  if (!probe.peak_reached) return no_peak(probe, probe_speed);
  const double length = loaded_length(spec);
  const double strain_at_peak = std::max(probe.peak_displacement_m / length, 1e-4);
  const double v_quasi_static =
      strain_at_peak * length / (2.0 * kTransitsToPeak * wave_transit_time(spec));
  // Then rate_study_runs runs at halving speeds, the first no faster than half the probe's.
  double v = std::min(0.5 * probe_speed, v_quasi_static);

  RateStudy study;
  study.speeds_m_s.push_back(probe_speed);
  study.peaks_n.push_back(probe.peak_load_n);
  study.wall_seconds.push_back(probe.wall_seconds);
  TestResult slowest = probe;
  for (std::int64_t k = 0; k < spec.loading.rate_study_runs && slowest.stop_reason != "cancelled";
       ++k, v *= 0.5) {
    run.loading.platen_velocity_m_s = v;
    slowest = run_compression_test(run, hooks);
    if (!slowest.peak_reached) return no_peak(slowest, v);
    study.speeds_m_s.push_back(v);
    study.peaks_n.push_back(slowest.peak_load_n);
    study.wall_seconds.push_back(slowest.wall_seconds);
  }
  extrapolate_to_zero_speed(study);
  double total_wall = 0.0;
  for (double w : study.wall_seconds) total_wall += w;
  slowest.wall_seconds = total_wall;
  slowest.rate_study = study;
  return slowest;
}

}  // namespace rockcal
