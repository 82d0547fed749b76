// Face-centred cubic packings cut to specimen shapes. The lattice's cube axes are aligned with the
// coordinate axes, and every test loads along z, so eq. 3 holds exactly along the loading axis.
#pragma once

#include <vector>

#include "engine/vec.hpp"

namespace rockcal {

// Specimen shapes, centred at the origin.
struct Cylinder {  // axis along z
  double diameter_m, height_m;
};
struct Disc {  // axis along y; loaded across the diameter along z
  double diameter_m, thickness_m;
};

// Centres of the FCC lattice (touching spheres of radius R, one centre at the origin) whose spheres
// lie inside the shape, within a tolerance of R / 2 so that a surface particle may poke out by at
// most half its radius. The seed paper does not say how it cut its sample: for D = 49, H = 139 this
// rule gives 43,113 particles against the paper's 44,394 (-2.9%; the lattice allows no closer cut).
std::vector<Vec3> fcc_centres(const Cylinder& shape, double radius_m);
std::vector<Vec3> fcc_centres(const Disc& shape, double radius_m);

}  // namespace rockcal
