// Floaters (Potyondy & Cundall 2004, material genesis): a particle joined to the specimen by fewer
// than three bonds is not held by it. Left in, such a grain sits loose on the surface, where a
// platen can load it alone and report a "peak" that no bond failure made.
#pragma once

#include <cstddef>
#include <vector>

#include "engine/packing/random_dense.hpp"

namespace rockcal {

constexpr int kMinBondsToHold = 3;

// Removes every sphere with fewer than `min_bonds` bond partners (pairs closer than
// (R_i + R_j)(1 + bond_tolerance)), repeating until none is left: a removal can leave a neighbour
// short. Keeps the order of the rest. Returns how many were removed.
std::size_t remove_floaters(std::vector<Sphere>& spheres, double bond_tolerance,
                            int min_bonds = kMinBondsToHold);

}  // namespace rockcal
