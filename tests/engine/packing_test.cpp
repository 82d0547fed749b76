// Random dense packings: determinism, radius distribution, density, overlaps, cut, coordination,
// and the file cache. Samples are small so the suite stays within seconds.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>

#include "engine/packing/cache.hpp"
#include "engine/packing/random_dense.hpp"

namespace rockcal {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kBondTolerance = 0.025;  // gap below 5% of the pair's mean radius

const RandomPackingParams kParams{1.0, 1.5, 7};
const Cylinder kCylinder{20.0, 30.0};

// One shared packing for the property tests, generated once.
const std::vector<Sphere>& cylinder_packing() {
  static const std::vector<Sphere> spheres = random_dense_spheres(kCylinder, kParams);
  return spheres;
}

bool identical(const std::vector<Sphere>& a, const std::vector<Sphere>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (a[k].centre != b[k].centre || a[k].radius != b[k].radius) return false;
  return true;
}

bool interior(const Vec3& x, double margin_m) {
  return std::hypot(x.x(), x.y()) < 0.5 * kCylinder.diameter_m - margin_m &&
         std::abs(x.z()) < 0.5 * kCylinder.height_m - margin_m;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

TEST(RandomDense, SameSeedGivesBitIdenticalPacking) {
  const Cylinder small{10.0, 12.0};
  const auto a = random_dense_spheres(small, kParams);
  const auto b = random_dense_spheres(small, kParams);
  ASSERT_FALSE(a.empty());
  EXPECT_TRUE(identical(a, b));
}

TEST(RandomDense, DifferentSeedsGiveDifferentPackings) {
  const Cylinder small{10.0, 12.0};
  RandomPackingParams other = kParams;
  other.seed = kParams.seed + 1;
  EXPECT_FALSE(identical(random_dense_spheres(small, kParams), random_dense_spheres(small, other)));
}

TEST(RandomDense, RadiiAreUniformBetweenMinAndMaxWithTheRequestedMean) {
  const auto& s = cylinder_packing();
  const double r_min = 2.0 * kParams.mean_radius_m / (1.0 + kParams.radius_ratio),
               r_max = kParams.radius_ratio * r_min;
  double sum = 0.0, lo = r_max, hi = r_min;
  int lower_half = 0;
  for (const Sphere& x : s) {
    EXPECT_GE(x.radius, r_min);
    EXPECT_LE(x.radius, r_max);
    sum += x.radius;
    lo = std::min(lo, x.radius);
    hi = std::max(hi, x.radius);
    lower_half += x.radius < kParams.mean_radius_m;
  }
  const double n = static_cast<double>(s.size());
  // The cut keeps a random subset: its mean scatters by sd / sqrt(n) (sd of U(0.8, 1.2) = 0.115).
  EXPECT_NEAR(sum / n, kParams.mean_radius_m, 4.0 * 0.4 / std::sqrt(12.0 * n));
  EXPECT_LT(lo, r_min + 0.02);
  EXPECT_GT(hi, r_max - 0.02);
  EXPECT_NEAR(lower_half / n, 0.5, 4.0 * 0.5 / std::sqrt(n));  // uniform: half below the mean
}

TEST(RandomDense, CentresLieInsideTheShape) {
  for (const Sphere& x : cylinder_packing()) {
    EXPECT_LE(std::hypot(x.centre.x(), x.centre.y()), 0.5 * kCylinder.diameter_m - 0.5 * x.radius);
    EXPECT_LE(std::abs(x.centre.z()), 0.5 * kCylinder.height_m - 0.5 * x.radius);
  }
}

TEST(RandomDense, OverlapsAreBelowOnePercentOfTheSmallestRadius) {
  const double r_min = 2.0 * kParams.mean_radius_m / (1.0 + kParams.radius_ratio);
  EXPECT_LT(max_overlap_m(cylinder_packing()), 0.01 * r_min);
}

TEST(RandomDense, InteriorIsDenseAndWellConnected) {
  const auto& s = cylinder_packing();
  const std::vector<int> z = coordination_numbers(s, kBondTolerance);
  // Solid fraction of an inner cylinder, counting the spheres centred in it (the boundary
  // spheres poking in and out roughly cancel).
  const double margin = 3.0;
  const double inner_volume = kPi / 4.0 * std::pow(kCylinder.diameter_m - 2.0 * margin, 2) *
                              (kCylinder.height_m - 2.0 * margin);
  double solid = 0.0, z_sum = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (!interior(s[k].centre, margin)) continue;
    solid += 4.0 / 3.0 * kPi * std::pow(s[k].radius, 3);
    z_sum += z[k];
    ++n;
  }
  ASSERT_GT(n, 500);
  const double porosity = 1.0 - solid / inner_volume, coordination = z_sum / n;
  std::printf("interior: %d particles, porosity %.3f, coordination %.2f\n", n, porosity,
              coordination);
  EXPECT_GT(porosity, 0.32);
  EXPECT_LT(porosity, 0.42);
  EXPECT_GT(coordination, 5.0);
  EXPECT_LT(coordination, 7.5);
}

TEST(RandomDense, WholeSpecimenStatsArePlausible) {
  const auto& s = cylinder_packing();
  const double volume =
      kPi / 4.0 * kCylinder.diameter_m * kCylinder.diameter_m * kCylinder.height_m;
  const PackingStats st = packing_stats(s, kBondTolerance, volume);
  std::printf("whole cylinder: %zu particles, porosity %.3f, coordination %.2f\n", st.particles,
              st.porosity, st.coordination_number);
  EXPECT_EQ(st.particles, s.size());
  // The cut leaves a looser skin and fewer partners at the surface than in the interior.
  EXPECT_GT(st.porosity, 0.32);
  EXPECT_LT(st.porosity, 0.55);
  EXPECT_GT(st.coordination_number, 4.0);
  EXPECT_LT(st.coordination_number, 7.5);
}

TEST(RandomDense, DiscIsCutAlongItsYAxis) {
  const Disc disc{16.0, 8.0};
  const auto s = random_dense_spheres(disc, kParams);
  ASSERT_GT(s.size(), 120u);
  double y_extent = 0.0, z_extent = 0.0;
  for (const Sphere& x : s) {
    EXPECT_LE(std::hypot(x.centre.x(), x.centre.z()), 0.5 * disc.diameter_m - 0.5 * x.radius);
    EXPECT_LE(std::abs(x.centre.y()), 0.5 * disc.thickness_m - 0.5 * x.radius);
    y_extent = std::max(y_extent, std::abs(x.centre.y()));
    z_extent = std::max(z_extent, std::abs(x.centre.z()));
  }
  EXPECT_GT(z_extent, 0.5 * disc.diameter_m - 1.5);  // filled to the rim
  EXPECT_GT(y_extent, 0.5 * disc.thickness_m - 1.5);
  const double r_min = 2.0 * kParams.mean_radius_m / (1.0 + kParams.radius_ratio);
  EXPECT_LT(max_overlap_m(s), 0.01 * r_min);
}

// The platens load the faces packed against the generator's walls. What a user relies on: no
// sphere pokes through a face's plane, and the spheres tangent to it (within `kFlat`) cover the
// face as a layer jammed against a wall does, not the one or two protruding spheres of a periodic
// packing cropped there (0-4% of the face, which crushed under the platens). How many of a
// layer's spheres the jammed network presses onto the wall varies: over seeds 1-6 of a D 20, H 40
// cylinder one face had 0.11-0.50 of its central part covered, the two together 0.59-0.79.
// kFlat, m with mean radius 1: the walls end wider apart than asked by < 1e-4 of the gap.
constexpr double kFlat = 0.005;

struct Face {
  int touching = 0;
  double covered = 0.0;   // the touching spheres' cross sections in the central part / its area
  double poke_out = 0.0;  // largest sphere extent beyond the plane
};

// The face z = side * plane_z; `central` picks the part away from the rim (where the lateral crop
// thins the layer) over which the coverage is taken, of area `central_area`.
Face face_of(const std::vector<Sphere>& spheres, double plane_z, double side,
             const std::function<bool(const Vec3&)>& central, double central_area) {
  Face f;
  f.poke_out = -std::numeric_limits<double>::infinity();
  for (const Sphere& s : spheres) {
    const double beyond = side * s.centre.z() + s.radius - plane_z;
    f.poke_out = std::max(f.poke_out, beyond);
    if (beyond < -kFlat || !central(s.centre)) continue;
    ++f.touching;
    f.covered += kPi * s.radius * s.radius / central_area;
  }
  return f;
}

// Both faces flat, each with a share of the layer pressed onto it and the two together covered
// as a wall-jammed pair of faces is.
void expect_flat_faces(const std::vector<Sphere>& spheres, double plane_z,
                       const std::function<bool(const Vec3&)>& central, double central_area) {
  double both = 0.0;
  for (const double side : {-1.0, 1.0}) {
    const Face f = face_of(spheres, plane_z, side, central, central_area);
    std::printf("face %+g: %d spheres within %g of the plane cover %.3f of it, poke out %.2e\n",
                side, f.touching, kFlat, f.covered, f.poke_out);
    EXPECT_LT(f.poke_out, kFlat);
    EXPECT_GT(f.covered, 0.1);
    both += f.covered;
  }
  EXPECT_GT(both, 0.5);
}

TEST(RandomDense, CylinderEndsAreFlatWallPackedLayers) {
  const double inner = 0.5 * kCylinder.diameter_m - 2.0;  // two radii in from the rim
  expect_flat_faces(
      cylinder_packing(), 0.5 * kCylinder.height_m,
      [&](const Vec3& x) { return std::hypot(x.x(), x.y()) < inner; }, kPi * inner * inner);
}

TEST(RandomDense, FlattenedDiscFlatsAreFlatWallPackedLayers) {
  Disc disc{24.0, 10.0};
  disc.flat_z_m = 10.0;  // flats 13 radii wide, so their central parts hold about ten spheres
  const auto s = random_dense_spheres(disc, kParams);
  const double half_width = std::sqrt(0.25 * disc.diameter_m * disc.diameter_m -
                                      disc.flat_z_m * disc.flat_z_m),
               inner_x = half_width - 1.0, inner_y = 0.5 * disc.thickness_m - 1.0;
  expect_flat_faces(
      s, disc.flat_z_m,
      [&](const Vec3& x) { return std::abs(x.x()) < inner_x && std::abs(x.y()) < inner_y; },
      4.0 * inner_x * inner_y);
  const double r_min = 2.0 * kParams.mean_radius_m / (1.0 + kParams.radius_ratio);
  EXPECT_LT(max_overlap_m(s), 0.01 * r_min);
}

TEST(RandomDense, RejectsInvalidParameters) {
  EXPECT_THROW(random_dense_spheres(kCylinder, {1.0, 0.5, 1}), std::invalid_argument);
  EXPECT_THROW(random_dense_spheres(kCylinder, {0.0, 1.5, 1}), std::invalid_argument);
}

class PackingCache : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("rockcal_packing_test_" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path dir_;
  const Cylinder shape_{10.0, 12.0};
};

TEST_F(PackingCache, HitReturnsIdenticalDataFast) {
  auto t0 = std::chrono::steady_clock::now();
  const auto first = cached_random_dense(shape_, kParams, dir_);
  const double generate_s = seconds_since(t0);
  ASSERT_TRUE(std::filesystem::exists(packing_cache_file(shape_, kParams, dir_)));
  t0 = std::chrono::steady_clock::now();
  const auto second = cached_random_dense(shape_, kParams, dir_);
  const double hit_s = seconds_since(t0);
  std::printf("generate %.3f s, cache hit %.2e s\n", generate_s, hit_s);
  EXPECT_TRUE(identical(first, second));
  EXPECT_TRUE(identical(first, random_dense_spheres(shape_, kParams)));
  EXPECT_LT(hit_s, 0.1 * generate_s);
  // No temporary files are left behind.
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir_)) ++files;
  EXPECT_EQ(files, 1);
}

TEST_F(PackingCache, KeyCoversEveryParameter) {
  const auto base = packing_cache_file(shape_, kParams, dir_);
  RandomPackingParams p = kParams;
  p.seed += 1;
  EXPECT_NE(packing_cache_file(shape_, p, dir_), base);
  p = kParams;
  p.radius_ratio = 1.4;
  EXPECT_NE(packing_cache_file(shape_, p, dir_), base);
  p = kParams;
  p.mean_radius_m = 1.1;
  EXPECT_NE(packing_cache_file(shape_, p, dir_), base);
  EXPECT_NE(packing_cache_file(Cylinder{10.0, 12.5}, kParams, dir_), base);
  EXPECT_NE(packing_cache_file(Disc{10.0, 12.0}, kParams, dir_), base);
  // A flattened disc is packed against walls on its flats: another packing than the round disc.
  EXPECT_NE(packing_cache_file(Disc{10.0, 12.0, 4.9}, kParams, dir_),
            packing_cache_file(Disc{10.0, 12.0}, kParams, dir_));
}

TEST_F(PackingCache, CorruptOrTruncatedFilesAreRegenerated) {
  const auto good = cached_random_dense(shape_, kParams, dir_);
  const auto path = packing_cache_file(shape_, kParams, dir_);
  const auto size = std::filesystem::file_size(path);

  {  // flip one byte in the middle of the sphere records
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(size / 2));
    f.put('\x5a');
  }
  EXPECT_TRUE(identical(cached_random_dense(shape_, kParams, dir_), good));
  EXPECT_EQ(std::filesystem::file_size(path), size);

  std::filesystem::resize_file(path, size - 13);
  EXPECT_TRUE(identical(cached_random_dense(shape_, kParams, dir_), good));
  EXPECT_EQ(std::filesystem::file_size(path), size);

  std::ofstream(path, std::ios::binary | std::ios::trunc) << "garbage";
  EXPECT_TRUE(identical(cached_random_dense(shape_, kParams, dir_), good));
  EXPECT_EQ(std::filesystem::file_size(path), size);
}

}  // namespace
}  // namespace rockcal
