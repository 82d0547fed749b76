// Finite-rotation properties: rigid motion of a pair loads nothing; twist and bending do not depend
// on the order they were applied in; loads rotate with the pair.
#include <gtest/gtest.h>

#include "bond_fixture.hpp"

using namespace rockcal;
using rockcal::testing::Pair;
using rockcal::testing::rot;

namespace {

// Rotates the whole pair (positions about the midpoint, and both orientations) by s.
Pair rigidly_rotated(Pair p, const Quat& s) {
  const Vec3 mid = 0.5 * (p.xi + p.xj);
  p.xi = mid + s * (p.xi - mid);
  p.xj = mid + s * (p.xj - mid);
  p.qi = s * p.qi;
  p.qj = s * p.qj;
  return p;
}

}  // namespace

TEST(BondInvariance, RigidRotationByLargeAnglesLoadsNothing) {
  for (double angle : {0.3, 1.7, 3.0, 6.0}) {
    for (const Vec3& axis : {Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(1, 2, -0.5)}) {
      const Pair p = rigidly_rotated(Pair{}, rot(angle, axis));
      const BondLoad l = p.load();
      EXPECT_NEAR(l.force_i.norm(), 0.0, 1e-9) << angle;
      EXPECT_NEAR(l.torque_i.norm() + l.torque_j.norm(), 0.0, 1e-9) << angle;
      EXPECT_NEAR(l.energy, 0.0, 1e-12);
    }
  }
}

TEST(BondInvariance, DeformedPairLoadsRotateWithIt) {
  Pair p;
  p.xj += Vec3(0.01, -0.02, 0.003);
  p.qi = rot(0.05, Vec3(1, 1, 0));
  p.qj = rot(0.08, Vec3(0, 1, 1));
  const BondLoad before = p.load();
  const Quat s = rot(2.4, Vec3(0.3, -1, 0.7));
  const BondLoad after = rigidly_rotated(p, s).load();
  EXPECT_NEAR((after.force_i - s * before.force_i).norm(), 0.0, 1e-9);
  EXPECT_NEAR((after.torque_i - s * before.torque_i).norm(), 0.0, 1e-9);
  EXPECT_NEAR((after.torque_j - s * before.torque_j).norm(), 0.0, 1e-9);
  EXPECT_NEAR(after.energy, before.energy, 1e-12);
}

TEST(BondInvariance, TwistThenBendEqualsBendThenTwist) {
  const double twist = 0.3, bend = 0.4;  // large, so that the order would matter in a naive split
  Pair a, b;
  a.qj = rot(bend, Vec3::UnitX()) * rot(twist, Vec3::UnitZ());  // twist first, then bend
  b.qj = rot(twist, Vec3::UnitZ()) * rot(bend, Vec3::UnitX());  // bend first, then twist
  const BondLoad la = a.load(), lb = b.load();
  EXPECT_NEAR(la.tau_t, a.k.kt_nm_rad * twist, 1e-12);
  EXPECT_NEAR(lb.tau_t, b.k.kt_nm_rad * twist, 1e-12);
  EXPECT_NEAR(la.tau_b, a.k.kb_nm_rad * bend, 1e-12);
  EXPECT_NEAR(lb.tau_b, b.k.kb_nm_rad * bend, 1e-12);
  EXPECT_NEAR(la.energy, lb.energy, 1e-12);
}
