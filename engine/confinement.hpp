// Lateral confinement of the triaxial test: a pressure on the cylinder's lateral surface, applied
// as equal inward radial forces on the particles marked as surface particles.
#pragma once

#include <cstdint>

#include "engine/particles.hpp"

namespace rockcal {

// Marks the owned particles whose centre lies farther than `inner_radius` from the z axis as
// confined; returns how many this rank owns.
std::int64_t mark_confined(Particles& p, double inner_radius);

// Adds force_n, pointing to the z axis from the particle's current position, to every owned
// confined particle. Runs every step of a triaxial test only (Simulation::confining_force_n != 0).
void accumulate_confining_forces(Particles& p, double force_n);

}  // namespace rockcal
