// Each of the six interactions alone against its hand value (eq. 1).
#include <gtest/gtest.h>

#include "bond_fixture.hpp"

using namespace rockcal;
using rockcal::testing::Pair;
using rockcal::testing::rot;

TEST(BondModes, NormalStretchAndCompression) {
  for (double dz : {1e-3, -2e-3}) {
    Pair p;
    p.xj.z() += dz;
    const BondLoad l = p.load();
    EXPECT_NEAR(l.f_r, p.k.kr_n_m * dz, 1e-9);
    EXPECT_NEAR(l.force_i.z(), p.k.kr_n_m * dz, 1e-9);  // stretched: i pulled towards j
    EXPECT_NEAR(l.force_j.z(), -p.k.kr_n_m * dz, 1e-9);
    EXPECT_NEAR(l.f_s, 0.0, 1e-12);
    EXPECT_NEAR(l.torque_i.norm() + l.torque_j.norm(), 0.0, 1e-12);
  }
}

TEST(BondModes, ShearInBothDirections) {
  for (const Vec3& dir : {Vec3(1, 0, 0), Vec3(0, 1, 0)}) {
    Pair p;
    const double d = 1e-3;
    p.xj += d * dir;
    const BondLoad l = p.load();
    // Shear displacement = r0 sin(phi), phi the tilt of the bond: exact for the finite geometry.
    const double phi = std::atan2(d, 2.0);
    EXPECT_NEAR(l.f_s, p.k.ks_n_m * 2.0 * std::sin(phi), 1e-9);
    EXPECT_NEAR(l.f_s, p.k.ks_n_m * d, 1e-6 * p.k.ks_n_m * d);
    // The shear force on j opposes its offset; the couple is balanced by equal torques on both.
    EXPECT_LT(l.force_j.dot(dir), 0.0);
    EXPECT_NEAR((l.force_i + l.force_j).norm(), 0.0, 1e-12);
    const Vec3 tq = l.torque_i + l.torque_j + (p.xi.cross(l.force_i) + p.xj.cross(l.force_j));
    EXPECT_NEAR(tq.norm(), 0.0, 1e-9);  // angular momentum conserved
    EXPECT_NEAR(l.tau_b, 0.0, 1e-12);
    EXPECT_NEAR(l.tau_t, 0.0, 1e-12);
  }
}

TEST(BondModes, TwistAboutTheBondAxis) {
  Pair p;
  const double a = 0.01;
  p.qj = rot(a, Vec3::UnitZ());
  const BondLoad l = p.load();
  EXPECT_NEAR(l.tau_t, p.k.kt_nm_rad * a, 1e-12);
  EXPECT_NEAR(l.torque_j.z(), -p.k.kt_nm_rad * a, 1e-12);
  EXPECT_NEAR(l.torque_i.z(), p.k.kt_nm_rad * a, 1e-12);
  EXPECT_NEAR(l.tau_b, 0.0, 1e-12);
  EXPECT_NEAR(l.f_s, 0.0, 1e-12);
  EXPECT_NEAR(l.f_r, 0.0, 1e-12);
}

TEST(BondModes, BendingInBothDirections) {
  for (const Vec3& axis : {Vec3(1, 0, 0), Vec3(0, 1, 0)}) {
    Pair p;
    const double b = 0.02;
    // Both particles rotate by opposite halves: pure bending, the bond direction stays on both
    // frames' mean, so there is no shear.
    p.qj = rot(0.5 * b, axis);
    p.qi = rot(-0.5 * b, axis);
    const BondLoad l = p.load();
    EXPECT_NEAR(l.tau_b, p.k.kb_nm_rad * b, 1e-12);
    EXPECT_NEAR(l.torque_j.dot(axis), -p.k.kb_nm_rad * b, 1e-12);
    EXPECT_NEAR(l.torque_i.dot(axis), p.k.kb_nm_rad * b, 1e-12);
    EXPECT_NEAR(l.tau_t, 0.0, 1e-12);
    EXPECT_NEAR(l.f_s, 0.0, 1e-9);
  }
}

TEST(BondModes, OneParticleRotatingShearsAndBends) {
  Pair p;
  const double t = 0.01;
  p.qj = rot(t, Vec3::UnitX());
  const BondLoad l = p.load();
  EXPECT_NEAR(l.tau_b, p.k.kb_nm_rad * t, 1e-12);
  // j's frame carries the reference direction off by t; the mean frame by t/2.
  EXPECT_NEAR(l.f_s, p.k.ks_n_m * 2.0 * std::sin(0.5 * t), 1e-9);
}

TEST(BondModes, StiffnessesFollowEquationThree) {
  const BondStiffness k = stiffness_from_youngs_modulus(12.33e9, 0.2, 0.001);
  EXPECT_NEAR(k.kr_n_m, std::sqrt(2.0) * 12.33e9 * 0.001 / (2.0 * 0.6), 1.0);
  EXPECT_NEAR(k.ks_n_m / k.kr_n_m, 0.4 / 1.2, 1e-12);
  EXPECT_NEAR(k.kb_nm_rad / k.kr_n_m, 0.6 * 1e-6 / (24.0 * 0.8), 1e-18);
  EXPECT_NEAR(k.kt_nm_rad / k.kb_nm_rad, 0.4 / 1.2, 1e-12);
}
