// Two-rate loading slows the platens once damage starts; the rate study halves the speed and
// extrapolates the peak to zero speed.
#include <gtest/gtest.h>

#include "engine/loadtests/driver.hpp"

using namespace rockcal;

namespace {

JobSpec small_uct() {
  JobSpec s;
  s.test = TestKind::uct;
  s.sample.diameter_m = 8;
  s.sample.height_m = 16;
  s.material.kr_n_m = 8000;
  s.loading.platen_velocity_m_s = 0.1;
  return s;
}

// Platen closure rate (both platens) over the last rows of the curve, m/s.
double final_closure_rate(const TestResult& r) {
  const CurvePoint& a = r.curve[r.curve.size() - 4];
  const CurvePoint& b = r.curve.back();
  return (b.displacement_m - a.displacement_m) / (b.time_s - a.time_s);
}

}  // namespace

TEST(LoadingRate, TwoRateLoadingSlowsDownOnceBondsBreak) {
  JobSpec fast = small_uct();
  JobSpec two = small_uct();
  two.loading.slow_factor = 0.25;
  const TestResult a = run_test(fast), b = run_test(two);
  ASSERT_EQ(a.stop_reason, "post_peak");
  ASSERT_EQ(b.stop_reason, "post_peak");
  EXPECT_NEAR(final_closure_rate(a), 2 * 0.1, 0.01);
  EXPECT_NEAR(final_closure_rate(b), 2 * 0.1 * 0.25, 0.005);
  EXPECT_GT(b.steps, a.steps);
  // The intact phase ran at full speed: the first rows of both curves are the same.
  EXPECT_DOUBLE_EQ(a.curve[5].load_n, b.curve[5].load_n);
}

TEST(LoadingRate, RateStudyHalvesTheSpeedAndExtrapolates) {
  JobSpec s = small_uct();
  s.loading.rate_study = true;
  s.loading.slow_factor = 0.5;
  const TestResult r = run_test(s);
  ASSERT_TRUE(r.rate_study);
  const RateStudy& st = *r.rate_study;
  ASSERT_EQ(st.speeds_m_s.size(), 4u);  // the probe plus three halvings
  EXPECT_DOUBLE_EQ(st.speeds_m_s[0], 0.1);
  for (std::size_t k = 2; k < st.speeds_m_s.size(); ++k)
    EXPECT_DOUBLE_EQ(st.speeds_m_s[k], 0.5 * st.speeds_m_s[k - 1]);
  EXPECT_DOUBLE_EQ(r.peak_load_n, st.peaks_n.back());  // the result is the slowest real run
  EXPECT_GT(st.extrapolated_peak_n, 0.0);
  EXPECT_LT(st.rate_error, 0.05);
  RecordProperty("rate_error", std::to_string(st.rate_error));
}
