#include "engine/loadtests/seating.hpp"

#include <cmath>

namespace rockcal {

double seating_load(const JobSpec& spec) {
  if (spec.loading.seating_load_n) return *spec.loading.seating_load_n;
  const double d = spec.sample.diameter_m, r = spec.sample.radius_m;
  const double section =
      spec.test == TestKind::btt ? d * spec.sample.btt_thickness() : 0.25 * M_PI * d * d;
  return kSeatingFraction * spec.bond.fr0_n * section / (4.0 * r * r);
}

}  // namespace rockcal
