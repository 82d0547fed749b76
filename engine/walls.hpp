// Platens: planes driven at a prescribed velocity. The load a test reports is their reaction.
#pragma once

#include <vector>

#include "engine/particles.hpp"

namespace rockcal {

struct Wall {
  Vec3 normal;               // unit, pointing into the specimen
  Vec3 point;                // a point on the plane, m
  Vec3 velocity;             // m/s (set by the test driver each step)
  double kn_n_m;             // repulsive stiffness
  double ks_n_m;             // tangential stiffness (friction)
  double friction;           // Coulomb coefficient; 0 = frictionless
  std::vector<Vec3> spring;  // per-particle tangential history (only with friction)
  Vec3 reaction;             // force the particles exert on the wall this step, N
  int touching = 0;          // particles in contact this step
};

Wall make_wall(const Vec3& normal, const Vec3& point, double kn, double ks, double friction,
               std::size_t n);

// Adds wall forces to the particles and stores the wall's reaction.
void accumulate_wall_forces(Wall& w, Particles& p, double dt);

}  // namespace rockcal
