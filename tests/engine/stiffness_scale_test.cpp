// Focus: the strengths set the peak load, not the stiffness scale. In a lattice whose bonds join
// every touching pair, every force law is linear in the displacements up to breakage at a force,
// so tripling every stiffness (bonds, contacts, platens) at a loading speed that follows the rock
// gives the same peak load at a third of the strain. (A random packing has gaps between unbonded
// neighbours, a length of its own: there the peak moves with K_r, docs/calibration.md "E and nu";
// the stiffness stage therefore runs before the strength search. The elastic half of the scale
// law is ElasticRandom.EScalesWithKrWhileNuFollowsKsOverKrAlone.)
#include <gtest/gtest.h>

#include "engine/loadtests/driver.hpp"

using namespace rockcal;

TEST(StiffnessScale, ALatticesPeakLoadStaysWhereTheStrengthsPutItWhenKrTriples) {
  auto peak = [](double kr) {
    JobSpec s;
    s.test = TestKind::uct;
    s.sample.diameter_m = 10;
    s.sample.height_m = 28;
    s.material.kr_n_m = kr;
    s.bond.fr0_n = 100;
    s.bond.fs0_n = 100;
    s.loading.platen_velocity_m_s = std::nullopt;  // "auto": the speed follows the rock
    s.loading.auto_transits = 80;
    s.loading.max_strain = 0.3;
    return run_test(s);
  };
  const TestResult base = peak(8000);
  const TestResult stiff = peak(24000);
  for (const TestResult* r : {&base, &stiff}) {
    ASSERT_TRUE(r->peak_reached);
    ASSERT_TRUE(r->loading_rate && r->loading_rate->quasi_static());
  }
  EXPECT_NEAR(stiff.peak_load_n / base.peak_load_n, 1.0, 0.05);
  RecordProperty("peak_ratio", std::to_string(stiff.peak_load_n / base.peak_load_n));
}
