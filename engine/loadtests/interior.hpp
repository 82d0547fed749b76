// Stress and strain measured inside a specimen, away from its surfaces.
#pragma once

#include <unordered_map>
#include <vector>

#include "engine/simulation.hpp"

namespace rockcal {

using Mat3 = Eigen::Matrix3d;

struct InteriorState {
  Mat3 strain;    // symmetric small strain, least-squares fit of the displacements
  Mat3 stress;    // Pa, positive in tension: bond-force virial over the particles' volumes
  int particles;  // how many particles the region held (all ranks)
};

// `inside` selects the region by reference position; `reference` maps owned particle ids to their
// reference positions. `particle_volume_m3` is the volume a particle occupies in the packing
// (sphere volume / solid fraction). Sums run over owned particles and are reduced over ranks.
template <class Region>
InteriorState measure_interior(const Simulation& sim,
                               const std::unordered_map<std::int64_t, Vec3>& reference,
                               Region inside, double particle_volume_m3);

}  // namespace rockcal

#include "engine/loadtests/interior_impl.hpp"
