#include "engine/packing/fcc.hpp"

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include "engine/effects/draw.hpp"

namespace rockcal {
namespace {

// Lattice sites one walk may visit: bounds its time and memory whatever the caller asks (the job
// spec's particle limit keeps real specimens far below).
constexpr double kMaxLatticeSites = 2.0e8;

// Walks the lattice over every cell that can reach the box of half-extents `half` (whatever the
// placement's angle) and keeps the centres `inside` accepts.
std::vector<Vec3> lattice_in(const Vec3& half, double radius, const LatticePlacement& place,
                             const std::function<bool(const Vec3&)>& inside) {
  const double a = 2.0 * std::sqrt(2.0) * radius;  // cube edge: nearest neighbours 2R apart
  const Vec3 basis[4] = {
      {0, 0, 0}, {0.5 * a, 0.5 * a, 0}, {0.5 * a, 0, 0.5 * a}, {0, 0.5 * a, 0.5 * a}};
  const double c = std::cos(place.angle_rad), s = std::sin(place.angle_rad);
  // In the lattice's frame the rotated box fits in a square of half-side |half_xy|. Cell counts
  // are +inf or NaN for absurd sizes: refused by the site test before any cast to int.
  const double cells_xy = (std::hypot(half.x(), half.y()) + a) / a;
  const double cells_z = (half.z() + a) / a;
  const double sites = 4.0 * (2.0 * cells_xy + 3.0) * (2.0 * cells_xy + 3.0) * (2.0 * cells_z + 3.0);
  if (!(radius > 0.0) || !(sites <= kMaxLatticeSites))
    throw std::length_error("FCC lattice of " + std::to_string(sites) + " sites (limit " +
                            std::to_string(kMaxLatticeSites) + ")");
  const int nxy = static_cast<int>(cells_xy) + 1;
  const int nz = static_cast<int>(cells_z) + 1;
  std::vector<Vec3> out;
  for (int k = -nz; k <= nz; ++k)
    for (int j = -nxy; j <= nxy; ++j)
      for (int i = -nxy; i <= nxy; ++i)
        for (const Vec3& b : basis) {
          const Vec3 l = Vec3(i * a, j * a, k * a) + b;  // lattice frame
          const Vec3 x(c * l.x() - s * l.y() + place.offset.x(),
                       s * l.x() + c * l.y() + place.offset.y(), l.z() + place.offset.z());
          if (inside(x)) out.push_back(x);
        }
  return out;
}

constexpr double kTolerance = 0.5;  // in radii
constexpr double kEps = 1e-9;

}  // namespace

LatticePlacement seeded_lattice(std::uint64_t seed, double radius_m) {
  const double a = 2.0 * std::sqrt(2.0) * radius_m;
  constexpr std::uint64_t kStream = 0x6663636c61747469ULL;  // "fcclatti"
  LatticePlacement p;
  p.offset =
      a * Vec3(effects::unit_draw(seed, kStream, 0, 0), effects::unit_draw(seed, kStream, 1, 0),
               effects::unit_draw(seed, kStream, 2, 0));
  p.angle_rad = 0.5 * M_PI * effects::unit_draw(seed, kStream, 3, 0);
  return p;
}

std::vector<Vec3> fcc_centres(const Cylinder& s, double r, const LatticePlacement& place) {
  const double rmax = 0.5 * s.diameter_m - (1.0 - kTolerance) * r + kEps;
  const double zmax = 0.5 * s.height_m - (1.0 - kTolerance) * r + kEps;
  return lattice_in(
      Vec3(0.5 * s.diameter_m, 0.5 * s.diameter_m, 0.5 * s.height_m), r, place, [&](const Vec3& x) {
        return x.x() * x.x() + x.y() * x.y() <= rmax * rmax && std::abs(x.z()) <= zmax;
      });
}

std::vector<Vec3> fcc_centres(const Disc& s, double r, const LatticePlacement& place) {
  const double rmax = 0.5 * s.diameter_m - (1.0 - kTolerance) * r + kEps;
  const double ymax = 0.5 * s.thickness_m - (1.0 - kTolerance) * r + kEps;
  const double zflat = s.flat_z_m - (1.0 - kTolerance) * r + kEps;
  return lattice_in(Vec3(0.5 * s.diameter_m, 0.5 * s.thickness_m, 0.5 * s.diameter_m), r, place,
                    [&](const Vec3& x) {
                      return x.x() * x.x() + x.z() * x.z() <= rmax * rmax &&
                             std::abs(x.y()) <= ymax && std::abs(x.z()) <= zflat;
                    });
}

}  // namespace rockcal
