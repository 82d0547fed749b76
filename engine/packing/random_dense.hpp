// Random dense polydisperse sphere packings cut to the specimen shapes (the UCT cylinder and the
// BTT disc of fcc.hpp). The method, after YADE's randomDensePack: a random cloud in a periodic box
// is compressed by frictionless soft-sphere relaxation to the jamming point, then cropped. Along
// z, the loading axis of every test, the box is closed by two flat walls on the planes of the
// loaded faces (the cylinder's ends, the flattened disc's flats), as a specimen packed in a mould
// is, so the platens meet flat faces; the round disc, loaded by jaws, stays periodic. Frictionless
// jamming is the densest state such a method reaches without crystallising, and it leaves every
// non-rattler particle with about 6 touching neighbours, which bonding then picks up.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/packing/fcc.hpp"
#include "engine/vec.hpp"

namespace rockcal {

// Bumped whenever the generator's output for the same parameters changes, so caches invalidate.
inline constexpr int kRandomDenseVersion = 2;

struct Sphere {
  Vec3 centre;    // m
  double radius;  // m
};

struct RandomPackingParams {
  double mean_radius_m;
  // max / min radius, >= 1; radii are uniformly distributed between min and max with the given mean
  double radius_ratio;
  std::uint64_t seed;
};

struct PackingStats {
  double porosity;             // 1 - (sum of sphere volumes) / shape volume
  double coordination_number;  // mean number of bond partners per particle
  std::size_t particles;
};

// Same parameters give bit-identical output on the same machine and build. The loaded faces (the
// cylinder's ends, the disc's flats when flat_z_m is finite) are flat: the cloud is jammed between
// walls on their planes, so the spheres that touch a face are tangent to its plane.
std::vector<Sphere> random_dense_spheres(const Cylinder& shape, const RandomPackingParams& p);
std::vector<Sphere> random_dense_spheres(const Disc& shape, const RandomPackingParams& p);

// Pairs count as bonded when their distance is below (R_i + R_j)(1 + bond_tolerance), the rule of
// bond_neighbours() in simulation.hpp; 0.025 means a gap below 5% of the pair's mean radius.
PackingStats packing_stats(const std::vector<Sphere>& spheres, double bond_tolerance,
                           double shape_volume_m3);
// The bond partner count of each sphere (same rule), so callers can average over the interior only.
std::vector<int> coordination_numbers(const std::vector<Sphere>& spheres, double bond_tolerance);
// Largest overlap R_i + R_j - |x_i - x_j| over all pairs (0 if none overlap), m.
double max_overlap_m(const std::vector<Sphere>& spheres);

}  // namespace rockcal
