#include "engine/loadtests/peak.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

namespace rockcal {

std::int64_t min_failure_breaks(std::int64_t bonds, double diameter_over_radius) {
  const double crack = static_cast<double>(bonds) * 2.0 / diameter_over_radius;
  return std::max(kMinFailureBreaks,
                  static_cast<std::int64_t>(std::ceil(kFailureCrackFraction * crack)));
}

void PeakTracker::start(std::int64_t broken_now) {
  broken_from = broken_at_max = broken_now;
  max_load = 0.0;
  forget(broken_now);
}

void PeakTracker::forget(std::int64_t broken_now) {
  peak_load = 0.0;
  peak_closure = 0.0;
  peak_step = 0;
  broken_at_peak = broken_now;
}

bool PeakTracker::update(double load, double closure, std::int64_t step, std::int64_t broken_now) {
  if (load > max_load) {
    max_load = load;
    broken_at_max = broken_now;
  }
  if (load > peak_load) {
    peak_load = load;
    peak_closure = closure;
    peak_step = step;
    broken_at_peak = broken_now;
    return false;
  }
  if (peak_load <= 0.0 || load > stop_fraction * peak_load) return false;
  // Past the peak: a failure if bonds broke on the way up and keep breaking on the way down.
  if (broken_now - broken_from >= min_breaks && broken_now > broken_at_peak) return true;
  if (broken_now == broken_at_peak) {  // fell without a single break: not the specimen's peak
    ++false_peaks;
    largest_false_peak = std::max(largest_false_peak, peak_load);
    forget(broken_now);
  }
  return false;
}

std::string PeakTracker::no_peak_reason(const std::string& stop_reason) const {
  // JSON's shortest form for a number; a load that is not one (a run gone unstable) as "NaN" or
  // "inf", never JSON's "null".
  auto num = [](double x) {
    if (std::isnan(x)) return std::string("NaN");
    if (std::isinf(x)) return std::string(x > 0 ? "inf" : "-inf");
    return nlohmann::json(x).dump();
  };
  std::string why;
  if (stop_reason == "max_strain")
    why = "the load did not fall past a peak with bonds breaking before loading.max_strain";
  else if (stop_reason == "max_steps")
    why = "loading.max_steps ended the run before the load fell past a peak with bonds breaking";
  else if (stop_reason == "past_window")
    why =
        "the load was still rising past the bond-controlled window (loading.past_window "
        "\"stop\"): no peak set by the bond strengths";
  else if (stop_reason == "not_seated")
    why = "the platens never reached the seating load";
  else
    why = "the run ended (" + stop_reason + ") before a peak with failure";
  why += "; largest load " + num(max_load) + " N with " +
         std::to_string(broken_at_max - broken_from) +
         " bonds broken since seating (a failure needs " + std::to_string(min_breaks) + ")";
  if (false_peaks > 0)
    why += "; the load fell " + std::to_string(false_peaks) +
           " time(s) without any bond breaking (largest such maximum " + num(largest_false_peak) +
           " N)";
  return why;
}

}  // namespace rockcal
