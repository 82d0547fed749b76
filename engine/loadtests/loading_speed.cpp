#include "engine/loadtests/loading_speed.hpp"

#include <algorithm>

#include "engine/loadtests/specimen.hpp"
#include "engine/units.hpp"

namespace rockcal {

double bond_failure_strain(const JobSpec& spec) {
  const double r = spec.sample.radius_m;
  const BondStiffness k = bond_stiffness(spec, r);
  return std::min(spec.bond.fr0_n / k.kr_n_m, spec.bond.fs0_n / k.ks_n_m) / (2.0 * r);
}

double platen_speed(const JobSpec& spec) {
  const LoadingSpec& ld = spec.loading;
  if (ld.platen_velocity_m_s) return *ld.platen_velocity_m_s;
  // Both platens move: the closure rate is twice the speed.
  const double closure = bond_failure_strain(spec) * loaded_length(spec);
  return closure / (2.0 * ld.auto_transits * wave_transit_time(spec));
}

double late_platen_speed(const JobSpec& spec) {
  const double v = platen_speed(spec);
  if (spec.loading.platen_velocity_m_s) return v;
  const double covering = spec.loading.max_strain * loaded_length(spec) /
                          (2.0 * kLateTransits * wave_transit_time(spec));
  return std::max(v, covering);
}

double follow_rate(const JobSpec& spec) {
  const LoadingSpec& ld = spec.loading;
  if (ld.platen_velocity_m_s || ld.follow_transits <= 0 || spec.test == TestKind::btt) return 0.0;
  return 1.0 / (2.0 * ld.follow_transits * wave_transit_time(spec));  // both platens move
}

}  // namespace rockcal
