#include "engine/packing/random_dense.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

namespace rockcal {
namespace {

constexpr double kPi = 3.14159265358979323846;

// std::uniform_real_distribution's output is implementation-defined; this mapping is not.
double uniform01(std::mt19937_64& g) {
  return static_cast<double>(g() >> 11) * 0x1.0p-53;
}

// Wraps one component of a separation into the nearest periodic image. Positions are re-wrapped at
// every list build and move less than a skin between builds, so one shift always suffices.
double nearest_image(double d, double length) {
  if (d > 0.5 * length) return d - length;
  if (d < -0.5 * length) return d + length;
  return d;
}

// A cell grid over either a box centred at the origin, periodic in x and y and optionally in z, or
// the bounding box of the points. Cells are at least `cell_m` wide, so every pair closer than that
// sits in adjacent cells. Points outside a box that is not periodic along z count into its edge
// cells, which is still exact: a pair in cells two apart along z is farther than `cell_m`.
class CellGrid {
 public:
  CellGrid(const std::vector<Vec3>& x, double cell_m, const Vec3* box, bool periodic_z = true)
      : periodic_{box != nullptr, box != nullptr, box != nullptr && periodic_z} {
    if (box != nullptr) {
      lo_ = -0.5 * *box;
      extent_ = *box;
    } else {
      lo_ = x.empty() ? Vec3::Zero() : x[0];
      Vec3 hi = lo_;
      for (const Vec3& p : x) {
        lo_ = lo_.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
      // A flat or single-point set still needs a finite cell width.
      extent_ = (hi - lo_).cwiseMax(Vec3::Constant(cell_m));
    }
    for (int a = 0; a < 3; ++a) {
      dims_[a] = std::max<std::int64_t>(1, static_cast<std::int64_t>(extent_[a] / cell_m));
      // A periodic grid needs three cells a side, or one neighbour cell would be visited twice.
      if (periodic_[a] && dims_[a] < 3) throw std::invalid_argument("periodic box too small");
    }
    const std::size_t ncell = static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]);
    start_.assign(ncell + 1, 0);
    home_.resize(x.size());
    for (std::size_t k = 0; k < x.size(); ++k) {
      home_[k] = cell_index(cell_of(x[k]));
      ++start_[home_[k] + 1];
    }
    for (std::size_t c = 0; c < ncell; ++c) start_[c + 1] += start_[c];
    members_.resize(x.size());
    std::vector<std::int32_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t k = 0; k < x.size(); ++k)
      members_[fill[home_[k]]++] = static_cast<std::int32_t>(k);
  }

  // Calls visit(i, j) once for every pair i < j in the same or adjacent cells.
  template <class Visit>
  void for_each_candidate(const std::vector<Vec3>& x, Visit&& visit) const {
    for (std::size_t i = 0; i < x.size(); ++i) {
      const std::array<std::int64_t, 3> c = cell_of(x[i]);
      for (std::int64_t dz = -1; dz <= 1; ++dz)
        for (std::int64_t dy = -1; dy <= 1; ++dy)
          for (std::int64_t dx = -1; dx <= 1; ++dx) {
            std::array<std::int64_t, 3> n = {c[0] + dx, c[1] + dy, c[2] + dz};
            if (!neighbour_cell(n)) continue;
            const std::size_t cell = cell_index(n);
            for (std::int32_t m = start_[cell]; m < start_[cell + 1]; ++m) {
              const std::int32_t j = members_[m];
              if (j > static_cast<std::int32_t>(i)) visit(static_cast<std::int32_t>(i), j);
            }
          }
    }
  }

 private:
  std::array<std::int64_t, 3> cell_of(const Vec3& p) const {
    std::array<std::int64_t, 3> c;
    for (int a = 0; a < 3; ++a) {
      const auto k = static_cast<std::int64_t>(std::floor((p[a] - lo_[a]) / extent_[a] * dims_[a]));
      c[a] = std::clamp<std::int64_t>(k, 0, dims_[a] - 1);
    }
    return c;
  }
  // Wraps (periodic) or rejects (bounded) a neighbour cell outside the grid.
  bool neighbour_cell(std::array<std::int64_t, 3>& n) const {
    for (int a = 0; a < 3; ++a) {
      if (n[a] >= 0 && n[a] < dims_[a]) continue;
      if (!periodic_[a]) return false;
      n[a] = (n[a] + dims_[a]) % dims_[a];
    }
    return true;
  }
  std::size_t cell_index(const std::array<std::int64_t, 3>& c) const {
    return static_cast<std::size_t>((c[2] * dims_[1] + c[1]) * dims_[0] + c[0]);
  }

  std::array<bool, 3> periodic_;
  Vec3 lo_, extent_;
  std::array<std::int64_t, 3> dims_;
  std::vector<std::int32_t> start_, members_;
  std::vector<std::int64_t> home_;
};

// A periodic assembly: centres in a box centred at the origin, radii s * a_k. With walls, z is not
// periodic: two flat walls normal to z confine the cloud instead (box z is then unused).
struct PeriodicCloud {
  std::vector<Vec3> x;
  std::vector<double> a;
  Vec3 box;
  double s;
  // Half the gap between the walls in units of the drawn radii (the gap is s times this in the
  // cloud's coordinates, so it ends at exactly this once the radii are rescaled to s = 1);
  // infinite for a cloud periodic in z.
  double wall_half_gap = std::numeric_limits<double>::infinity();
  bool walled() const { return std::isfinite(wall_half_gap); }
  int periodic_axes() const { return walled() ? 2 : 3; }
};

// Frictionless soft spheres (unit stiffness and mass) relaxed by FIRE (Bitzek et al. 2006) while
// the radius scale s is steered so that the mean overlap settles at a small target: this finds the
// jamming point from above, where the contact network is mechanically stable.
class Jammer {
 public:
  explicit Jammer(PeriodicCloud& c) : c_(c), n_(c.x.size()) {
    a_max_ = *std::max_element(c_.a.begin(), c_.a.end());
    double sum = 0.0;
    for (double a : c_.a) sum += a;
    a_mean_ = sum / static_cast<double>(n_);
    skin_ = 0.4 * a_mean_;
    v_.assign(n_, Vec3::Zero());
    f_.assign(n_, Vec3::Zero());
    build();
  }

  // Compresses to a mean overlap per particle of `target` * mean radius, stopping when forces
  // balance to `force_tol` of the mean contact force. Returns false if max_iterations ran out.
  bool compress(double target, double force_tol, int max_iterations) {
    constexpr double kGain = 0.15, kMaxGrowth = 2e-3;  // per iteration
    for (int it = 0; it < max_iterations; ++it) {
      const Load l = forces();
      const double pressure = l.overlap_sum / (static_cast<double>(n_) * c_.s * a_mean_);
      const double f_rms = std::sqrt(l.force2_sum / static_cast<double>(n_));
      const double f_mean = l.contacts > 0 ? l.overlap_sum / static_cast<double>(l.contacts) : 0;
      if (std::abs(pressure - target) < 0.1 * target && f_rms < force_tol * f_mean) return true;
      // Near jamming, growing s by g raises the pressure by about 6 g (3 contacts per particle);
      // a log law with gain 0.15 target corrects 90% of a small error per step without
      // overshooting, yet grows fast while the cloud is loose and the pressure tiny.
      const double error = pressure > 0.0 ? std::log(target / pressure) : 1e9;
      c_.s *= 1.0 + std::clamp(kGain * target * error, -kMaxGrowth, kMaxGrowth);
      fire_step();
    }
    return false;
  }

  // Relaxes at a fixed radius scale until no overlap exceeds `overlap_tol` of the pair's radius
  // sum (below jamming this reaches zero energy).
  bool relax(double overlap_tol, int max_iterations) {
    for (int it = 0; it < max_iterations; ++it) {
      if (forces().max_relative_overlap < overlap_tol) return true;
      fire_step();
    }
    return false;
  }

  double mean_relative_overlap() {
    const Load l = forces();
    return l.contacts > 0 ? l.relative_overlap_sum / static_cast<double>(l.contacts) : 0.0;
  }
  double max_relative_overlap() { return forces().max_relative_overlap; }

  // From here on the walls stay where they are while the radii shrink, so that shrinking the
  // radii removes wall overlaps exactly as it does pair overlaps.
  void freeze_walls() { wall_scale_ = c_.s; }

  void wrap_positions() {
    for (Vec3& p : c_.x)
      for (int a = 0; a < c_.periodic_axes(); ++a)
        p[a] -= c_.box[a] * std::floor(p[a] / c_.box[a] + 0.5);
  }

  long iterations() const { return iterations_; }

 private:
  // Positions are wrapped only at builds, so a pair's periodic image shift is fixed until the next.
  struct Pair {
    std::int32_t i, j;
    double sum_a;  // a_i + a_j
    Vec3 shift;    // added to x_j - x_i to get the nearest image
  };

  struct Load {
    double overlap_sum = 0.0, relative_overlap_sum = 0.0, max_relative_overlap = 0.0,
           force2_sum = 0.0;
    std::size_t contacts = 0;
  };

  // Walls at z = +-wall_z(). While compressing they move with the radius scale, so the gap ends at
  // the specimen's length in radii; the price is that only x and y are compressed, which leaves
  // the interior contact network a little anisotropic (<n_z^2> about 0.31 against 1/3, measured:
  // docs/packing.md).
  double wall_z() const { return c_.wall_half_gap * (wall_scale_ > 0.0 ? wall_scale_ : c_.s); }

  void build() {
    wrap_positions();
    pairs_.clear();
    const double cutoff = 2.0 * a_max_ * c_.s + skin_;
    Vec3 grid_box = c_.box;
    if (c_.walled()) grid_box.z() = 2.0 * wall_z();
    const CellGrid grid(c_.x, cutoff, &grid_box, !c_.walled());
    grid.for_each_candidate(c_.x, [&](std::int32_t i, std::int32_t j) {
      const double sum_a = c_.a[i] + c_.a[j], reach = sum_a * c_.s + skin_;
      const Vec3 d = c_.x[j] - c_.x[i];
      Vec3 image = d;
      for (int a = 0; a < c_.periodic_axes(); ++a) image[a] = nearest_image(d[a], c_.box[a]);
      if (image.squaredNorm() < reach * reach) pairs_.push_back({i, j, sum_a, image - d});
    });
    ref_ = c_.x;
    s_build_ = c_.s;
  }

  // The list stays valid while no pair can have closed the skin: two particles each moving by the
  // largest displacement, plus the radius growth since the build.
  void rebuild_if_needed() {
    double d2 = 0.0;
    for (std::size_t k = 0; k < n_; ++k) d2 = std::max(d2, (c_.x[k] - ref_[k]).squaredNorm());
    if (2.0 * std::sqrt(d2) + 2.0 * a_max_ * std::max(0.0, c_.s - s_build_) > skin_) build();
  }

  Load forces() {
    rebuild_if_needed();
    Load l;
    for (Vec3& f : f_) f.setZero();
    for (const Pair& p : pairs_) {
      const std::int32_t i = p.i, j = p.j;
      const Vec3 d = c_.x[j] - c_.x[i] + p.shift;
      const double sum_r = p.sum_a * c_.s, dist2 = d.squaredNorm();
      if (dist2 >= sum_r * sum_r) continue;
      const double dist = std::sqrt(dist2), overlap = sum_r - dist, relative = overlap / sum_r;
      const Vec3 f = (overlap / dist) * d;  // unit stiffness, pushes i and j apart
      f_[i] -= f;
      f_[j] += f;
      l.overlap_sum += overlap;
      l.relative_overlap_sum += relative;
      l.max_relative_overlap = std::max(l.max_relative_overlap, relative);
      ++l.contacts;
    }
    if (c_.walled()) add_wall_forces(l);
    for (const Vec3& f : f_) l.force2_sum += f.squaredNorm();
    return l;
  }

  // The walls are frictionless half-spaces with the spheres' unit stiffness; a wall overlap counts
  // relative to the sphere's radius, the wall's analogue of a pair's radius sum.
  void add_wall_forces(Load& l) {
    const double w = wall_z();
    for (std::size_t k = 0; k < n_; ++k) {
      const double r = c_.a[k] * c_.s, z = c_.x[k].z();
      for (const double side : {-1.0, 1.0}) {
        const double overlap = r - (w - side * z);  // side +1: the top wall, pushing down
        if (overlap <= 0.0) continue;
        f_[k].z() -= side * overlap;
        l.overlap_sum += overlap;
        l.relative_overlap_sum += overlap / r;
        l.max_relative_overlap = std::max(l.max_relative_overlap, overlap / r);
        ++l.contacts;
      }
    }
  }

  // One FIRE step (semi-implicit Euler, unit masses) with the forces of the last forces() call.
  void fire_step() {
    constexpr int kDelay = 5;
    constexpr double kGrow = 1.1, kShrink = 0.5, kAlpha0 = 0.1, kAlphaDecay = 0.99, kDtMax = 0.5;
    double power = 0.0, v2 = 0.0, f2 = 0.0;
    for (std::size_t k = 0; k < n_; ++k) {
      power += f_[k].dot(v_[k]);
      v2 += v_[k].squaredNorm();
      f2 += f_[k].squaredNorm();
    }
    if (power > 0.0) {
      const double mix = f2 > 0.0 ? alpha_ * std::sqrt(v2 / f2) : 0.0;
      for (std::size_t k = 0; k < n_; ++k) v_[k] = (1.0 - alpha_) * v_[k] + mix * f_[k];
      if (++since_uphill_ > kDelay) {
        dt_ = std::min(dt_ * kGrow, kDtMax);
        alpha_ *= kAlphaDecay;
      }
    } else {
      for (Vec3& v : v_) v.setZero();
      dt_ *= kShrink;
      alpha_ = kAlpha0;
      since_uphill_ = 0;
    }
    for (std::size_t k = 0; k < n_; ++k) {
      v_[k] += dt_ * f_[k];
      c_.x[k] += dt_ * v_[k];
    }
    ++iterations_;
  }

  PeriodicCloud& c_;
  std::size_t n_;
  double a_max_ = 0.0, a_mean_ = 0.0, skin_ = 0.0, s_build_ = 0.0;
  double wall_scale_ = 0.0;  // the radius scale the walls froze at; 0 while they follow it
  std::vector<Vec3> v_, f_, ref_;
  std::vector<Pair> pairs_;
  double dt_ = 0.1, alpha_ = 0.1;
  int since_uphill_ = 0;
  long iterations_ = 0;
};

// The cloud's particle count is set so the jammed box (at the solid fraction this method reaches
// for a radius ratio of 1.5, measured: docs/packing.md) is the bounding box plus a margin of one
// largest radius a side. Denser outcomes (wider radius ranges) shrink the box by a few percent,
// which the margin absorbs; every particle outside the shape is wasted work, so it stays small.
constexpr double kExpectedSolidFraction = 0.62;
constexpr double kStartSolidFraction = 0.3;
// Particles one cloud may hold: bounds the time and memory of a packing whatever the caller asks
// (the job spec's particle limit keeps real specimens far below).
constexpr double kMaxCloudParticles = 2.0e7;

// `wall_half_gap`: walls at z = +-wall_half_gap (infinite: periodic in z as in x and y).
PeriodicCloud random_cloud(const Vec3& bounding_box, double wall_half_gap,
                           const RandomPackingParams& p) {
  if (!(p.mean_radius_m > 0.0) || !(p.radius_ratio >= 1.0))
    throw std::invalid_argument("random packing: need mean radius > 0 and radius ratio >= 1");
  const double r_min = 2.0 * p.mean_radius_m / (1.0 + p.radius_ratio),
               r_max = p.radius_ratio * r_min;
  // Mean of r^3 for r uniform in [r_min, r_max].
  const double mean_r3 = r_max > r_min
                             ? (std::pow(r_max, 4) - std::pow(r_min, 4)) / (4.0 * (r_max - r_min))
                             : std::pow(r_min, 3);
  PeriodicCloud c;
  c.wall_half_gap = wall_half_gap;
  c.box = bounding_box + Vec3::Constant(2.0 * r_max);
  // Three cells a side of at least 2 r_max plus the skin (see CellGrid).
  c.box = c.box.cwiseMax(Vec3::Constant(3.0 * (2.0 * r_max + 0.5 * p.mean_radius_m)));
  // Between walls the volume to fill is the wall gap, with no margin: the walls are the faces.
  if (c.walled()) c.box.z() = 2.0 * wall_half_gap;
  const double count = kExpectedSolidFraction * c.box.prod() / (4.0 / 3.0 * kPi * mean_r3);
  if (!(count <= kMaxCloudParticles))  // also a count that is not a number
    throw std::length_error("random packing of " + std::to_string(count) + " particles (limit " +
                            std::to_string(kMaxCloudParticles) + ")");
  const auto n = static_cast<std::size_t>(std::llround(count));
  std::mt19937_64 g(p.seed);
  c.x.resize(n);
  c.a.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    for (int a = 0; a < 3; ++a) c.x[k][a] = (uniform01(g) - 0.5) * c.box[a];
    // Stratified draws: each radius falls in its own 1/n slice of [r_min, r_max], so the sample
    // mean is the requested mean to O(1/n) while positions stay independent of the radii.
    c.a[k] =
        r_min + (r_max - r_min) * (static_cast<double>(k) + uniform01(g)) / static_cast<double>(n);
  }
  // Walls that move with the radius scale leave only x and y to compress: the solid fraction grows
  // as s^2 between walls, as s^3 in a fully periodic box.
  const double start = kStartSolidFraction / kExpectedSolidFraction;
  c.s = c.walled() ? std::sqrt(start) : std::cbrt(start);
  // The walls start at +-s wall_half_gap, where the cloud's z positions are drawn.
  if (c.walled())
    for (Vec3& x : c.x) x.z() *= c.s;
  return c;
}

// Sorts particles along a coarse cell order so that neighbours sit close in memory.
void sort_spatially(PeriodicCloud& c, double cell_m) {
  std::vector<std::int64_t> key(c.x.size());
  std::array<std::int64_t, 3> dims;
  for (int a = 0; a < 3; ++a)
    dims[a] = std::max<std::int64_t>(1, static_cast<std::int64_t>(c.box[a] / cell_m));
  for (std::size_t k = 0; k < c.x.size(); ++k) {
    std::array<std::int64_t, 3> q;
    for (int a = 0; a < 3; ++a)
      q[a] = std::clamp<std::int64_t>(
          static_cast<std::int64_t>((c.x[k][a] / c.box[a] + 0.5) * dims[a]), 0, dims[a] - 1);
    key[k] = (q[2] * dims[1] + q[1]) * dims[0] + q[0];
  }
  std::vector<std::size_t> order(c.x.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t i, std::size_t j) { return key[i] < key[j]; });
  PeriodicCloud sorted{{}, {}, c.box, c.s, c.wall_half_gap};
  for (std::size_t k : order) {
    sorted.x.push_back(c.x[k]);
    sorted.a.push_back(c.a[k]);
  }
  c = std::move(sorted);
}

// Jams the cloud and rescales it so the radii are the drawn ones (s = 1), with no overlap left.
void jam(PeriodicCloud& c) {
  sort_spatially(c, 4.0 * *std::max_element(c.a.begin(), c.a.end()));
  Jammer j(c);
  // A mean overlap per particle of 1e-3 radii is about 2e-4 of each contact's radius sum: close
  // enough to the jamming point that backing off to zero overlap barely loosens the packing.
  // Stopping at a residual force of 15% of the mean contact force, rather than at full balance,
  // halves the iterations; the slow creep it skips would densify by only about 0.01
  // (docs/packing.md).
  j.compress(1e-3, 0.15, 20000);
  // Back off by twice the mean overlap (below jamming) and let the contacts open.
  c.s *= 1.0 - 2.0 * j.mean_relative_overlap();
  // The walls now stay put: the gap ends wider than asked by the last shrink only, < 1e-4 of it.
  j.freeze_walls();
  j.relax(1e-4, 2000);
  // Whatever overlap is left, shrinking the scale by the largest relative overlap removes it
  // exactly: each pair's radius sum falls by at least its own overlap.
  c.s *= 1.0 - j.max_relative_overlap();
  j.wrap_positions();
  for (Vec3& x : c.x) x /= c.s;
  c.box /= c.s;
  c.s = 1.0;
}

// Keeps the spheres of the periodic packing (and their periodic images, in case the jammed box
// came out smaller than the shape) whose centres `inside` accepts.
std::vector<Sphere> crop(const PeriodicCloud& c,
                         const std::function<bool(const Vec3&, double)>& inside) {
  std::vector<Sphere> out;
  const int images_z = c.walled() ? 0 : 1;  // walls leave no image beyond them
  for (std::size_t k = 0; k < c.x.size(); ++k)
    for (int iz = -images_z; iz <= images_z; ++iz)
      for (int iy = -1; iy <= 1; ++iy)
        for (int ix = -1; ix <= 1; ++ix) {
          const Vec3 x = c.x[k] + Vec3(ix * c.box[0], iy * c.box[1], iz * c.box[2]);
          if (inside(x, c.a[k])) out.push_back({x, c.a[k]});
        }
  return out;
}

// As in fcc.cpp: a centre may sit up to half its radius inside the shape's surface.
constexpr double kCutTolerance = 0.5;

// Both specimens are right circular cylinders; they differ in the axis (z for the UCT cylinder, y
// for the BTT disc). Both are loaded along z by platens on two planes z = +-flat_z (the cylinder's
// ends, the disc's flats). A packing cropped there out of a periodic cloud has rough faces, whose
// few protruding spheres crush under the platens long before the bonds inside fail; so the cloud
// is jammed between flat walls on those planes, as a specimen packed in a mould is, and the layers
// that packed against them become the loaded faces. Infinite flat_z (the round disc): no walls.
std::vector<Sphere> packed_cylinder(double diameter_m, double length_m, int axis, double flat_z,
                                    const RandomPackingParams& p) {
  Vec3 bounding_box = Vec3::Constant(diameter_m);
  bounding_box[axis] = length_m;
  PeriodicCloud c = random_cloud(bounding_box, flat_z, p);
  jam(c);
  return crop(c, [&](const Vec3& x, double r) {
    const double inset = (1.0 - kCutTolerance) * r, rho = 0.5 * diameter_m - inset,
                 half = 0.5 * length_m - inset;
    Vec3 radial = x;
    radial[axis] = 0.0;
    return radial.squaredNorm() <= rho * rho && std::abs(x[axis]) <= half &&
           std::abs(x.z()) <= flat_z - inset;
  });
}

}  // namespace

std::vector<Sphere> random_dense_spheres(const Cylinder& s, const RandomPackingParams& p) {
  return packed_cylinder(s.diameter_m, s.height_m, 2, 0.5 * s.height_m, p);
}

std::vector<Sphere> random_dense_spheres(const Disc& s, const RandomPackingParams& p) {
  return packed_cylinder(s.diameter_m, s.thickness_m, 1, s.flat_z_m, p);
}

namespace {

// Calls visit(i, j, distance) for every pair closer than (R_i + R_j)(1 + tolerance).
template <class Visit>
void for_each_near_pair(const std::vector<Sphere>& spheres, double tolerance, Visit&& visit) {
  if (spheres.empty()) return;
  std::vector<Vec3> x(spheres.size());
  double r_max = 0.0;
  for (std::size_t k = 0; k < spheres.size(); ++k) {
    x[k] = spheres[k].centre;
    r_max = std::max(r_max, spheres[k].radius);
  }
  const CellGrid grid(x, 2.0 * r_max * (1.0 + std::max(0.0, tolerance)), nullptr);
  grid.for_each_candidate(x, [&](std::int32_t i, std::int32_t j) {
    const double reach = (spheres[i].radius + spheres[j].radius) * (1.0 + tolerance);
    const double d2 = (x[j] - x[i]).squaredNorm();
    if (d2 < reach * reach) visit(i, j, std::sqrt(d2));
  });
}

}  // namespace

std::vector<int> coordination_numbers(const std::vector<Sphere>& spheres, double bond_tolerance) {
  std::vector<int> z(spheres.size(), 0);
  for_each_near_pair(spheres, bond_tolerance, [&](std::int32_t i, std::int32_t j, double) {
    ++z[i];
    ++z[j];
  });
  return z;
}

double max_overlap_m(const std::vector<Sphere>& spheres) {
  double worst = 0.0;
  for_each_near_pair(spheres, 0.0, [&](std::int32_t i, std::int32_t j, double d) {
    worst = std::max(worst, spheres[i].radius + spheres[j].radius - d);
  });
  return worst;
}

PackingStats packing_stats(const std::vector<Sphere>& spheres, double bond_tolerance,
                           double shape_volume_m3) {
  double solid = 0.0;
  for (const Sphere& s : spheres) solid += 4.0 / 3.0 * kPi * s.radius * s.radius * s.radius;
  const std::vector<int> z = coordination_numbers(spheres, bond_tolerance);
  double z_sum = 0.0;
  for (int k : z) z_sum += k;
  return {1.0 - solid / shape_volume_m3, spheres.empty() ? 0.0 : z_sum / spheres.size(),
          spheres.size()};
}

}  // namespace rockcal
