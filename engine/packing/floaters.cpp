#include "engine/packing/floaters.hpp"

namespace rockcal {

std::size_t remove_floaters(std::vector<Sphere>& spheres, double bond_tolerance, int min_bonds) {
  std::size_t removed = 0;
  for (;;) {
    const std::vector<int> z = coordination_numbers(spheres, bond_tolerance);
    std::size_t kept = 0;
    for (std::size_t k = 0; k < spheres.size(); ++k)
      if (z[k] >= min_bonds) spheres[kept++] = spheres[k];
    if (kept == spheres.size()) return removed;
    removed += spheres.size() - kept;
    spheres.resize(kept);
  }
}

}  // namespace rockcal
