#include "orchestrator/calibration/latin_hypercube.hpp"

#include <numeric>
#include <random>

namespace rockcal::calibration {
namespace {

double unit_draw(std::mt19937_64& rng) {
  return double(rng() >> 11) * 0x1.0p-53;
}

// Fisher-Yates with explicit draws (std::shuffle's use of the engine is unspecified).
std::vector<int> permutation(int n, std::mt19937_64& rng) {
  std::vector<int> p(n);
  std::iota(p.begin(), p.end(), 0);
  for (int i = n - 1; i > 0; --i) std::swap(p[i], p[rng() % std::uint64_t(i + 1)]);
  return p;
}

}  // namespace

std::vector<std::array<double, 2>> latin_hypercube(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::array<double, 2>> points(n);
  for (int axis = 0; axis < 2; ++axis) {
    const std::vector<int> strata = permutation(n, rng);
    for (int i = 0; i < n; ++i) points[i][axis] = (strata[i] + unit_draw(rng)) / n;
  }
  return points;
}

}  // namespace rockcal::calibration
