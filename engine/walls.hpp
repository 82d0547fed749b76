// Platens: planes driven at a prescribed velocity. The load a test reports is their reaction.
#pragma once

#include <vector>

#include "engine/particles.hpp"

namespace rockcal {

struct Wall {
  Vec3 normal;      // unit, pointing into the specimen
  Vec3 point;       // a point on the plane, m
  Vec3 velocity;    // m/s (set by the test driver each step)
  double kn_n_m;    // repulsive stiffness
  double ks_n_m;    // tangential stiffness (friction)
  double friction;  // Coulomb coefficient; 0 = frictionless
  int slot;         // index into Particles::wall_spring, where the friction history lives
  Vec3 reaction;    // force the particles exert on the wall, N (all ranks' once the step is done)
};

Wall make_wall(const Vec3& normal, const Vec3& point, double kn, double ks, double friction,
               int slot);

// Adds wall forces to the owned particles and stores this rank's share of the wall's reaction.
void accumulate_wall_forces(Wall& w, Particles& p, double dt);

}  // namespace rockcal
