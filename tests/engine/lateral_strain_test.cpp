// A compression test's lateral strain (curve.csv lateral_strain, the mid-height third's): in the
// elastic branch the specimen expands by about nu times the axial strain (the platens' friction
// restrains its ends a little), and the Brazilian test measures none.
#include <gtest/gtest.h>

#include "engine/loadtests/driver.hpp"
#include "engine/spec.hpp"

using namespace rockcal;

namespace {

// The seeded FCC cylinder of D/R 10, as a user would write it.
JobSpec small_uct() {
  return parse_job(nlohmann::json::parse(R"({"test": "uct",
    "sample": {"diameter": 10, "height": 20, "radius": 1},
    "material": {"density": 1, "kr": 8000, "nu": 0.2}, "bond": {"fr0": 64, "fs0": 128},
    "loading": {"platen_velocity": 0.05, "max_strain": 0.1}})"));
}

TEST(LateralStrain, TheElasticBranchExpandsByAboutNuTimesTheAxialStrain) {
  const JobSpec s = small_uct();
  const TestResult r = run_test(s);
  ASSERT_TRUE(r.peak_reached) << r.no_peak_reason;
  ASSERT_FALSE(r.curve.empty());
  ASSERT_TRUE(r.curve.front().lateral_strain);
  EXPECT_EQ(*r.curve.front().lateral_strain, 0.0);  // the seated state is the reference
  int checked = 0;
  for (const CurvePoint& c : r.curve) {
    if (c.load_n < 0.05 * r.peak_load_n || c.load_n > 0.3 * r.peak_load_n) continue;
    if (c.step > r.peak_step) break;
    ASSERT_TRUE(c.lateral_strain) << "step " << c.step;
    const double ratio = -*c.lateral_strain / (c.displacement_m / s.sample.height_m);
    EXPECT_GT(ratio, 0.12) << "step " << c.step;
    EXPECT_LT(ratio, 0.25) << "step " << c.step;
    ++checked;
  }
  EXPECT_GE(checked, 5);
}

TEST(LateralStrain, TheBrazilianTestMeasuresNone) {
  JobSpec s = small_uct();
  s.test = TestKind::btt;
  const TestResult r = run_test(s);
  ASSERT_FALSE(r.curve.empty());
  for (const CurvePoint& c : r.curve) EXPECT_FALSE(c.lateral_strain) << "step " << c.step;
}

}  // namespace
