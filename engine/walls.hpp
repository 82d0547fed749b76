// Platens and jaws: rigid surfaces driven at a prescribed velocity. The load a test reports is
// their reaction.
#pragma once

#include <vector>

#include "engine/particles.hpp"

namespace rockcal {

// plane: a flat platen. jaw: the concave cylindrical face of an ISRM Brazilian jaw, whose axis is
// parallel to `axis` through `point`, of radius `jaw_radius`; it holds the particles beyond the
// axis on the side opposite `normal` within `jaw_half_angle` of it (seen from the axis).
enum class WallShape { plane, jaw };

struct Wall {
  WallShape shape = WallShape::plane;
  Vec3 normal;      // unit, pointing into the specimen (a jaw: at its centre line)
  Vec3 point;       // a point on the plane, or on a jaw's axis, m
  Vec3 velocity;    // m/s (set by the test driver each step)
  double kn_n_m;    // repulsive stiffness
  double ks_n_m;    // tangential stiffness (friction)
  double friction;  // Coulomb coefficient; 0 = frictionless
  int slot;         // index into Particles::wall_spring, where the friction history lives
  Vec3 reaction;    // force the particles exert on the wall, N (all ranks' once the step is done)
  Vec3 axis = Vec3::UnitY();    // jaw only
  double jaw_radius = 0.0;      // jaw only, m
  double jaw_half_angle = 0.0;  // jaw only, rad
};

Wall make_wall(const Vec3& normal, const Vec3& point, double kn, double ks, double friction,
               int slot);
// A jaw whose face touches `contact` (the disc's extreme point on that side), `normal` pointing
// into the disc.
Wall make_jaw(const Vec3& normal, const Vec3& contact, const Vec3& axis, double radius,
              double half_angle, double kn, double ks, double friction, int slot);

// Adds wall forces to the owned particles and stores this rank's share of the wall's reaction.
void accumulate_wall_forces(Wall& w, Particles& p, double dt);

}  // namespace rockcal
