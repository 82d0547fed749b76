// A peak is a failure of the specimen only when damage accompanies it. A load can also rise and
// fall on a loose surface particle that the platen pushes aside, or on a lattice facet that
// rearranges, with no bond broken: reporting that maximum as the specimen's peak would be a false
// strength. The tracker therefore ends a test only at a post-peak drop that comes with bonds
// breaking, and forgets a drop that came without (the loading goes on to the real failure).
#pragma once

#include <cstdint>
#include <string>

namespace rockcal {

// Damage a failure needs around its peak: kFailureCrackFraction of the bonds a crack across the
// specimen's diameter cuts (about bonds x 2R / D: the bonds within a particle diameter of a
// diametral plane), at least kMinFailureBreaks. A few grains breaking off under a platen or a jaw
// cut far fewer; a split disc or a shear band cuts them all.
constexpr double kFailureCrackFraction = 0.2;
constexpr std::int64_t kMinFailureBreaks = 3;

std::int64_t min_failure_breaks(std::int64_t bonds, double diameter_over_radius);

struct PeakTracker {
  double stop_fraction;          // the test ends once the load falls to this fraction of the peak
  std::int64_t min_breaks;       // min_failure_breaks(bonds)
  std::int64_t broken_from = 0;  // damage counts from here (the seated state)
  double peak_load = 0.0;
  double peak_closure = 0.0;
  std::int64_t peak_step = 0;
  std::int64_t broken_at_peak = 0;
  int false_peaks = 0;  // drops past stop_fraction without damage, forgotten
  double largest_false_peak = 0.0;
  double max_load = 0.0;  // the largest load seen, peak or not (for a run without one)
  std::int64_t broken_at_max = 0;

  // Starts tracking at the seated state: damage counts from here.
  void start(std::int64_t broken_now);
  // Forgets the peak so far (a false one, or the fast phase of two-rate loading); damage still
  // counts from the start.
  void forget(std::int64_t broken_now);
  // Takes one step's load; returns true when the load has fallen past a peak with damage.
  bool update(double load, double closure, std::int64_t step, std::int64_t broken_now);
  // Why a run that ended otherwise has no peak (stop_reason: max_strain, max_steps, cancelled).
  std::string no_peak_reason(const std::string& stop_reason) const;
};

}  // namespace rockcal
