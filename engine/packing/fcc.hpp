// Face-centred cubic packings cut to specimen shapes. Every test loads along z, and a cube axis of
// the lattice always lies along z, so eq. 3 holds exactly along the loading axis.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "engine/vec.hpp"

namespace rockcal {

// Specimen shapes, centred at the origin.
struct Cylinder {  // axis along z
  double diameter_m, height_m;
};
struct Disc {  // axis along y; loaded across the diameter along z
  double diameter_m, thickness_m;
  // Flattened Brazilian disc: material beyond |z| = flat_z_m is cut away, leaving two parallel
  // flats for the platens. Infinite for the full disc.
  double flat_z_m = std::numeric_limits<double>::infinity();
};

// Where the lattice sits in the specimen. A lattice always cut the same way gives one specimen per
// size, whose surface facets (the contact flats under the platens) are an accident of the diameter;
// shifting the lattice by a random fraction of its cell and turning it about the loading axis makes
// each seed a different, equally valid cut, so an ensemble averages over the accident.
struct LatticePlacement {
  Vec3 offset = Vec3::Zero();  // lattice origin, m (within one cubic cell)
  double angle_rad = 0.0;      // rotation about z (the loading axis), in [0, pi/2)
};

// The seed-paper placement: one centre at the origin, cube axes along x, y, z.
inline LatticePlacement aligned_lattice() {
  return {};
}
// A placement drawn from `seed` alone: offset uniform in the cubic cell, angle uniform in [0, 90).
LatticePlacement seeded_lattice(std::uint64_t seed, double radius_m);

// Centres of the FCC lattice (touching spheres of radius R) whose spheres lie inside the shape,
// within a tolerance of R / 2 so that a surface particle may poke out by at most half its radius.
// The seed paper does not say how it cut its sample: for D = 49, H = 139 the aligned cut gives
// 43,113 particles against the paper's 44,394 (docs/specimens.md compares cuts).
std::vector<Vec3> fcc_centres(const Cylinder& shape, double radius_m,
                              const LatticePlacement& placement = {});
std::vector<Vec3> fcc_centres(const Disc& shape, double radius_m,
                              const LatticePlacement& placement = {});

}  // namespace rockcal
