// A Latin hypercube in the unit square: n points, one in each row and column stratum, so a
// handful of runs already spans the whole log box. Deterministic in `seed` on every platform
// (std distributions are not, so the draws come straight from mt19937_64 bits).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace rockcal::calibration {

std::vector<std::array<double, 2>> latin_hypercube(int n, std::uint64_t seed);

}  // namespace rockcal::calibration
