// Stress and strain measured inside a specimen, away from its surfaces.
#pragma once

#include <cmath>
#include <unordered_map>
#include <vector>

#include "engine/simulation.hpp"
#include "engine/spec.hpp"

namespace rockcal {

using Mat3 = Eigen::Matrix3d;

struct InteriorState {
  Mat3 strain;    // symmetric small strain, least-squares fit of the displacements
  Mat3 stress;    // Pa, positive in tension: bond-force virial over the particles' volumes
  int particles;  // how many particles the region held (all ranks)
};

// The axial (z) and the mean lateral (x, y) normal components of a strain, tension positive.
inline double axial_component(const Mat3& strain) {
  return strain(2, 2);
}
inline double lateral_component(const Mat3& strain) {
  return 0.5 * (strain(0, 0) + strain(1, 1));
}

// The interior a lab's gauges cover: the central half of the specimen in radius and in height
// (the specimen centred at the origin, loaded along z), by reference position.
struct CentralHalf {
  double r_in = 0.0, z_in = 0.0;
  bool operator()(const Vec3& x) const {
    return x.x() * x.x() + x.y() * x.y() <= r_in * r_in && std::abs(x.z()) <= z_in;
  }
};
inline CentralHalf central_half(const JobSpec& spec) {
  return {0.25 * spec.sample.diameter_m, 0.25 * spec.sample.height_m};
}

// measure_interior's work buffers. A caller that measures during the loading keeps one, so the
// loop does not allocate (they are resized in place and grow only with the particle count).
struct InteriorScratch {
  std::vector<char> in;
  std::vector<Vec3> ref;
};

// `inside` selects the region by reference position; `reference` maps owned particle ids to their
// reference positions. `particle_volume_m3` is the volume a particle occupies in the packing
// (sphere volume / solid fraction). Sums run over owned particles and are reduced over ranks: a
// collective, every rank calls it at the same step.
template <class Region>
InteriorState measure_interior(const Simulation& sim,
                               const std::unordered_map<std::int64_t, Vec3>& reference,
                               Region inside, double particle_volume_m3, InteriorScratch& scratch);

// measure_interior's strain alone (the stress left zero): the strain gauges read along a loading,
// without the bond forces' pass.
template <class Region>
InteriorState interior_strain(const Simulation& sim,
                              const std::unordered_map<std::int64_t, Vec3>& reference,
                              Region inside, InteriorScratch& scratch);

}  // namespace rockcal

#include "engine/loadtests/interior_impl.hpp"
