// The time step's batched bond kernel against the one-bond reference (bond_load, which the analytic
// tests check): same forces and torques, same breaks, and a bond's result does not depend on where
// it sits in the list, so two ranks that hold a border bond agree on breaking it.
#include <gtest/gtest.h>

#include <random>

#include "engine/bond_batch.hpp"
#include "engine/units.hpp"

using namespace rockcal;

namespace {

// `pairs` bonded pairs, pair k is particles 2k and 2k + 1, deformed at random: rotations of each
// size class (the largest fall outside the batch kernel's series and take the fallback).
struct Pairs {
  Particles p;
  std::vector<Bond> bonds;

  Pairs(int pairs, double strength, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const BondStiffness k = stiffness_from_kr(8000.0, 0.2, 1.0);
    const double rotation[] = {1e-4, 1e-2, 0.1, 0.5, 2.0};
    for (int b = 0; b < pairs; ++b) {
      const double ri = 1.0 + 0.3 * u(rng), rj = 1.0 + 0.3 * u(rng);
      const Vec3 xi(10 * u(rng), 10 * u(rng), 10 * u(rng));
      const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
      const Vec3 xj = xi + (ri + rj) * dir;
      p.add(xi, ri, 1.0, 1.0, 2 * b);
      p.add(xj, rj, 1.0, 1.0, 2 * b + 1);
      bonds.push_back(make_bond(2 * b, 2 * b + 1, 2 * b, 2 * b + 1, xi, ri, xj, rj, k.kr_n_m,
                                k.ks_n_m, k.kb_nm_rad, k.kt_nm_rad, strength, strength));
      const double angle = rotation[b % 5];
      p.pos[2 * b + 1] += 0.01 * Vec3(u(rng), u(rng), u(rng));
      for (int end : {2 * b, 2 * b + 1})
        p.orient[end] =
            Quat(Eigen::AngleAxisd(angle * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
    }
  }
};

}  // namespace

TEST(BondBatch, LoadsMatchTheReferenceKernelInEveryRotationClass) {
  Pairs s(203, 1e12, 7);  // 203 = 25 full batches and a short one; too strong to break
  const std::vector<Bond> before = s.bonds;
  std::vector<Bond> broken;
  std::vector<BreakEvent> events;
  s.p.clear_loads();
  accumulate_bond_forces(s.bonds, s.p, BreakRule{}, 0, broken, events);
  ASSERT_EQ(s.bonds.size(), before.size());
  EXPECT_TRUE(broken.empty());
  for (const Bond& b : before) {
    const BondLoad ref = bond_load(b, s.p.pos[b.i], s.p.orient[b.i], s.p.pos[b.j], s.p.orient[b.j]);
    const double scale = ref.force_i.norm() + 1e-6,
                 tscale = ref.torque_i.norm() + ref.torque_j.norm() + 1e-6;
    EXPECT_LT((s.p.force[b.i] - ref.force_i).norm(), 1e-11 * scale) << "bond " << b.id_i;
    EXPECT_LT((s.p.force[b.j] - ref.force_j).norm(), 1e-11 * scale) << "bond " << b.id_i;
    EXPECT_LT((s.p.torque[b.i] - ref.torque_i).norm(), 1e-11 * tscale) << "bond " << b.id_i;
    EXPECT_LT((s.p.torque[b.j] - ref.torque_j).norm(), 1e-11 * tscale) << "bond " << b.id_i;
  }
}

TEST(BondBatch, BreaksTheBondsTheReferenceBreaksAndKeepsTheRestInOrder) {
  Pairs s(203, 40.0, 11);
  std::vector<std::int64_t> expect_broken, expect_kept;
  for (const Bond& b : s.bonds) {
    const BondLoad ref = bond_load(b, s.p.pos[b.i], s.p.orient[b.i], s.p.pos[b.j], s.p.orient[b.j]);
    (breakage_index(b, ref, BreakRule{}, nullptr) >= 1.0 ? expect_broken : expect_kept)
        .push_back(b.id_i);
  }
  ASSERT_GT(expect_broken.size(), 20u);  // the set-up exercises breaking in every batch position
  ASSERT_GT(expect_kept.size(), 20u);
  std::vector<Bond> broken;
  std::vector<BreakEvent> events;
  s.p.clear_loads();
  accumulate_bond_forces(s.bonds, s.p, BreakRule{}, 3, broken, events);
  std::vector<std::int64_t> got_broken, got_kept;
  for (const Bond& b : broken) got_broken.push_back(b.id_i);
  for (const Bond& b : s.bonds) got_kept.push_back(b.id_i);
  EXPECT_EQ(got_broken, expect_broken);
  EXPECT_EQ(got_kept, expect_kept);  // intact bonds keep their (locality) order
  EXPECT_EQ(events.size(), expect_broken.size());
  // A broken bond adds nothing: its particles carry no load.
  for (const Bond& b : broken) {
    EXPECT_EQ(s.p.force[b.i].norm(), 0.0);
    EXPECT_EQ(s.p.torque[b.j].norm(), 0.0);
  }
}

TEST(BondBatch, ABondsResultDoesNotDependOnItsLane) {
  Pairs s(8, 1e12, 5);
  BondBatchIn in;
  BondBatchOut out;
  for (int b = 0; b < 8; ++b) {
    for (int l = 0; l < kBondLanes; ++l) gather_bond(s.bonds[b], s.p, l, in);
    load_batch(in, BreakRule{}, out);
    for (int l = 1; l < kBondLanes; ++l) {
      EXPECT_EQ(out.index[l], out.index[0]) << "bond " << b << " lane " << l;
      EXPECT_EQ(out.force_i[0][l], out.force_i[0][0]);
      EXPECT_EQ(out.torque_j[2][l], out.torque_j[2][0]);
    }
  }
}
