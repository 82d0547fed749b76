// Stress and strain measured inside a specimen, away from its surfaces.
#pragma once

#include <vector>

#include "engine/simulation.hpp"

namespace rockcal {

using Mat3 = Eigen::Matrix3d;

struct InteriorState {
  Mat3 strain;    // symmetric small strain, least-squares fit of the displacements
  Mat3 stress;    // Pa, positive in tension: bond-force virial over the particles' volumes
  int particles;  // how many particles the region held
};

// `inside` selects the region by reference position. `particle_volume_m3` is the volume a
// particle occupies in the packing (sphere volume / solid fraction).
template <class Region>
InteriorState measure_interior(const Simulation& sim, const std::vector<Vec3>& reference,
                               Region inside, double particle_volume_m3);

}  // namespace rockcal

#include "engine/loadtests/interior_impl.hpp"
