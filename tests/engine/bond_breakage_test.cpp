// Eq. 2: a bond breaks exactly where f_r/F_r0 + |f_s|/F_s0 + |tau_t|/G_t0 + |tau_b|/G_b0 reaches 1.
#include <gtest/gtest.h>

#include "bond_fixture.hpp"
#include "engine/simulation.hpp"

using namespace rockcal;
using rockcal::testing::Pair;
using rockcal::testing::rot;

namespace {

double index_of(const Pair& p, BreakMode* mode = nullptr, BreakRule rule = {}) {
  return breakage_index(p.bond, p.load(), rule, mode);
}

// Pure tension at a fraction `s` of F_r0.
Pair stretched(double s) {
  Pair p;
  p.xj.z() += s * p.bond.fr0 / p.k.kr_n_m;
  return p;
}

}  // namespace

TEST(BondBreakage, StrengthsOfTwistAndBendingFollowTheRadius) {
  Pair p;
  EXPECT_DOUBLE_EQ(p.bond.gb0, 1.0 * 64.0 / 4.0);
  EXPECT_DOUBLE_EQ(p.bond.gt0, 1.0 * 64.0 / 2.0);
}

TEST(BondBreakage, EachModeAloneBreaksAtItsStrength) {
  BreakMode mode;
  EXPECT_NEAR(index_of(stretched(0.999), &mode), 0.999, 1e-9);
  EXPECT_EQ(mode, BreakMode::tension);
  EXPECT_GE(index_of(stretched(1.0 + 1e-9)), 1.0);

  Pair twist;
  twist.qj = rot(0.999 * twist.bond.gt0 / twist.k.kt_nm_rad, Vec3::UnitZ());
  EXPECT_NEAR(index_of(twist, &mode), 0.999, 1e-9);
  EXPECT_EQ(mode, BreakMode::twist);

  Pair bend;
  const double b = 0.999 * bend.bond.gb0 / bend.k.kb_nm_rad;
  bend.qj = rot(0.5 * b, Vec3::UnitX());
  bend.qi = rot(-0.5 * b, Vec3::UnitX());
  EXPECT_NEAR(index_of(bend, &mode), 0.999, 1e-9);
  EXPECT_EQ(mode, BreakMode::bending);

  Pair shear;
  // Shear displacement r0 sin(phi) = 0.999 F_s0 / K_s; the small stretch it causes adds f_r/F_r0.
  const double ds = 0.999 * shear.bond.fs0 / shear.k.ks_n_m;
  const double phi = std::asin(ds / 2.0);
  shear.xj = Vec3(2.0 * std::sin(phi), 0, 2.0 * std::cos(phi));  // rotate about i, keep length
  EXPECT_NEAR(index_of(shear, &mode), 0.999, 1e-9);
  EXPECT_EQ(mode, BreakMode::shear);
}

TEST(BondBreakage, CombinedLoadsAddUp) {
  Pair p = stretched(0.5);
  p.qj = rot(0.49 * p.bond.gt0 / p.k.kt_nm_rad, Vec3::UnitZ());
  EXPECT_NEAR(index_of(p), 0.99, 1e-9);
  p.qj = rot(0.51 * p.bond.gt0 / p.k.kt_nm_rad, Vec3::UnitZ());
  EXPECT_NEAR(index_of(p), 1.01, 1e-9);
}

TEST(BondBreakage, CompressionRaisesTheOtherTermsCapacity) {
  // Compressed to half of F_r0: twisting now holds up to 1.5 G_t0.
  Pair p;
  p.xj.z() -= 0.5 * p.bond.fr0 / p.k.kr_n_m;
  p.qj = rot(1.49 * p.bond.gt0 / p.k.kt_nm_rad, Vec3::UnitZ());
  EXPECT_NEAR(index_of(p), 0.99, 1e-9);
  // With the coupling switched off (f_r clamped at zero in compression) the same bond breaks.
  EXPECT_NEAR(index_of(p, nullptr, BreakRule{0.0}), 1.49, 1e-9);
}

TEST(BondBreakage, ABrokenBondIsGoneForGoodAndRecorded) {
  Simulation sim;
  Pair p = stretched(1.01);
  sim.particles.add(p.xi, 1.0, 1.0, 0.4, 7);
  sim.particles.add(p.xj, 1.0, 1.0, 0.4, 8);
  p.bond.id_i = 7;
  p.bond.id_j = 8;
  sim.bonds.push_back(p.bond);
  sim.contact = ContactLaw{p.k.kr_n_m, p.k.ks_n_m, 0.6, 0.6};
  sim.dt = 1e-4;
  sim.neighbours.skin = 0.5;
  sim.initialise();
  ASSERT_TRUE(sim.bonds.empty());
  ASSERT_EQ(sim.breaks.size(), 1u);
  EXPECT_EQ(sim.breaks[0].mode, BreakMode::tension);
  EXPECT_EQ(sim.breaks[0].id_i, 7);
  EXPECT_EQ(sim.breaks[0].id_j, 8);
  EXPECT_NEAR((sim.breaks[0].where - 0.5 * (p.xi + p.xj)).norm(), 0.0, 1e-12);
  // Pushed back together, the pair meets only as a frictional contact (no tensile force, ever).
  sim.particles.pos[1] = p.xi + Vec3(0, 0, 2.2);
  sim.compute_loads();
  EXPECT_EQ(sim.particles.force[0].norm(), 0.0);
  sim.particles.pos[1] = p.xi + Vec3(0, 0, 1.99);
  sim.compute_loads();
  EXPECT_NEAR(sim.particles.force[1].z(), p.k.kr_n_m * 0.01, 1e-6);
  EXPECT_TRUE(sim.bonds.empty());
}
