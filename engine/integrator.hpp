// Velocity Verlet for translation and rotation (second order), with optional Cundall local damping
// and mass-proportional viscous damping applied to the forces of each step. All act on the owned
// particles only; ghosts are refreshed from their owners.
#pragma once

#include "engine/particles.hpp"

namespace rockcal {

struct Damping {
  double local = 0.0;    // F_d = -alpha |F| sign(v), per component
  double viscous = 0.0;  // F_d = -c m v, 1/s
};

// v += F/m * h and omega += T/I * h.
void kick(Particles& p, double h);
// x += v dt; orientation rotated by omega dt exactly, then renormalised.
void drift(Particles& p, double dt);
// Replaces the accumulated loads by their damped values (uses the current, mid-step velocities).
void apply_damping(Particles& p, const Damping& d);

double kinetic_energy(const Particles& p);  // owned particles: translational + rotational, J

}  // namespace rockcal
