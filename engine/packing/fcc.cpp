#include "engine/packing/fcc.hpp"

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

namespace rockcal {
namespace {

// Lattice sites one walk may visit: bounds its time and memory whatever the caller asks (the job
// spec's particle limit keeps real specimens far below).
constexpr double kMaxLatticeSites = 2.0e8;

// Walks the lattice over a box of half-extents `half` and keeps the centres `inside` accepts.
std::vector<Vec3> lattice_in(const Vec3& half, double radius,
                             const std::function<bool(const Vec3&)>& inside) {
  const double a = 2.0 * std::sqrt(2.0) * radius;  // cube edge: nearest neighbours 2R apart
  const Vec3 basis[4] = {
      {0, 0, 0}, {0.5 * a, 0.5 * a, 0}, {0.5 * a, 0, 0.5 * a}, {0, 0.5 * a, 0.5 * a}};
  std::vector<Vec3> out;
  const Vec3 cells = half / a;  // +inf or NaN for absurd sizes: refused by the next test
  const double sites =
      4.0 * (2.0 * cells.x() + 3.0) * (2.0 * cells.y() + 3.0) * (2.0 * cells.z() + 3.0);
  if (!(radius > 0.0) || !(sites <= kMaxLatticeSites))
    throw std::length_error("FCC lattice of " + std::to_string(sites) + " sites (limit " +
                            std::to_string(kMaxLatticeSites) + ")");
  const int nx = static_cast<int>(cells.x()) + 1, ny = static_cast<int>(cells.y()) + 1,
            nz = static_cast<int>(cells.z()) + 1;
  for (int k = -nz; k <= nz; ++k)
    for (int j = -ny; j <= ny; ++j)
      for (int i = -nx; i <= nx; ++i)
        for (const Vec3& b : basis) {
          const Vec3 x = Vec3(i * a, j * a, k * a) + b;
          if (inside(x)) out.push_back(x);
        }
  return out;
}

constexpr double kTolerance = 0.5;  // in radii
constexpr double kEps = 1e-9;

}  // namespace

std::vector<Vec3> fcc_centres(const Cylinder& s, double r) {
  const double rmax = 0.5 * s.diameter_m - (1.0 - kTolerance) * r + kEps;
  const double zmax = 0.5 * s.height_m - (1.0 - kTolerance) * r + kEps;
  return lattice_in(
      Vec3(0.5 * s.diameter_m, 0.5 * s.diameter_m, 0.5 * s.height_m), r, [&](const Vec3& x) {
        return x.x() * x.x() + x.y() * x.y() <= rmax * rmax && std::abs(x.z()) <= zmax;
      });
}

std::vector<Vec3> fcc_centres(const Disc& s, double r) {
  const double rmax = 0.5 * s.diameter_m - (1.0 - kTolerance) * r + kEps;
  const double ymax = 0.5 * s.thickness_m - (1.0 - kTolerance) * r + kEps;
  return lattice_in(
      Vec3(0.5 * s.diameter_m, 0.5 * s.thickness_m, 0.5 * s.diameter_m), r, [&](const Vec3& x) {
        return x.x() * x.x() + x.z() * x.z() <= rmax * rmax && std::abs(x.y()) <= ymax;
      });
}

}  // namespace rockcal
