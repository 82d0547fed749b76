// The building blocks: Latin hypercube, log space, homogeneity measurement, objective.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "orchestrator/calibration/homogeneity.hpp"
#include "orchestrator/calibration/latin_hypercube.hpp"
#include "orchestrator/calibration/objective.hpp"
#include "orchestrator/calibration/search_space.hpp"
#include "orchestrator/calibration/start_design.hpp"
#include "synthetic.hpp"

namespace rockcal::calibration {
namespace {

TEST(LatinHypercube, OnePointPerStratumAndDeterministic) {
  const auto a = latin_hypercube(7, 3);
  EXPECT_EQ(a, latin_hypercube(7, 3));
  EXPECT_NE(a, latin_hypercube(7, 4));
  for (int axis = 0; axis < 2; ++axis) {
    std::set<int> strata;
    for (const auto& p : a) {
      EXPECT_GE(p[axis], 0.0);
      EXPECT_LT(p[axis], 1.0);
      strata.insert(int(p[axis] * 7));
    }
    EXPECT_EQ(strata.size(), 7u);
  }
}

TEST(SearchSpace, RatioCoordinatesRoundTripAndRespectTheBox) {
  const CalibrationCampaign c =
      testing::campaign({1000, 100}, {{"bounds", {{"fr0", {2, 500}}, {"fs0", {10, 1000}}}}});
  const LogBox box = log_box(c);
  const BondPoint p{40, 90};
  const BondPoint q = point_from_ratio_coords(ratio_coords(p));
  EXPECT_NEAR(q.fr0_n, 40, 1e-9);
  EXPECT_NEAR(q.fs0_n, 90, 1e-9);
  const Range sr = s_range(box);
  EXPECT_NEAR(sr.lo, std::log(10.0 / 500), 1e-12);
  EXPECT_NEAR(sr.hi, std::log(1000.0 / 2), 1e-12);
  for (double s : {sr.lo, -1.0, 0.0, 2.0, sr.hi}) {
    const Range mr = m_range(box, s);
    for (double m : {mr.lo, mr.hi}) {
      const BondPoint b = point_from_ratio_coords({s, m});
      EXPECT_GE(b.fr0_n, 2 * (1 - 1e-12));
      EXPECT_LE(b.fr0_n, 500 * (1 + 1e-12));
      EXPECT_GE(b.fs0_n, 10 * (1 - 1e-12));
      EXPECT_LE(b.fs0_n, 1000 * (1 + 1e-12));
    }
  }
  const BondPoint clipped = clip_to_bounds({500.0000001, 9.9999}, c);
  EXPECT_EQ(clipped.fr0_n, 500);
  EXPECT_EQ(clipped.fs0_n, 10);
}

EvaluationRecord record_at(const BondPoint& p, testing::Model model) {
  EvaluationRecord r;
  r.point = p;
  r.loads = model(p);
  return r;
}

TEST(Homogeneity, MeasuresTheExponentsOfAScaledPair) {
  const BondPoint x{30, 30};
  const Homogeneity h = measure_homogeneity(record_at(x, testing::power_law),
                                            record_at({60, 60}, testing::power_law), 0.1);
  EXPECT_TRUE(h.holds);
  EXPECT_NEAR(h.exponent_uct, 1.0, 1e-12);
  EXPECT_NEAR(h.exponent_btt, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(h.scale_factor, 2.0);

  const Homogeneity n = measure_homogeneity(record_at(x, testing::non_homogeneous),
                                            record_at({60, 60}, testing::non_homogeneous), 0.1);
  EXPECT_TRUE(n.measured);
  EXPECT_FALSE(n.holds);
  EXPECT_NEAR(n.exponent_btt, 1.2, 1e-12);
  EXPECT_LT(n.exponent_uct, 0.9);

  EvaluationRecord failed = record_at({60, 60}, testing::power_law);
  failed.loads.reset();
  EXPECT_FALSE(measure_homogeneity(record_at(x, testing::power_law), failed, 0.1).measured);
}

TEST(Homogeneity, ProbeFitsInsideTheBounds) {
  const CalibrationCampaign c =
      testing::campaign({1000, 100}, {{"bounds", {{"fr0", {10, 15}}, {"fs0", {10, 1000}}}}});
  const std::vector<BondPoint> start = start_design(c);
  ASSERT_EQ(start.size(), 6u);
  const double factor = start[1].fr0_n / start[0].fr0_n;
  EXPECT_NEAR(start[1].fs0_n / start[0].fs0_n, factor, 1e-12);
  EXPECT_NEAR(factor, std::sqrt(1.5), 1e-9);  // as far as the narrow fr0 range allows
}

TEST(Objective, LogRatiosAreSymmetricAndToleranceIsRelative) {
  const PeakLoads target{100, 10};
  EXPECT_NEAR(misfit(log_errors({200, 10}, target), {1, 1}),
              misfit(log_errors({50, 10}, target), {1, 1}), 1e-12);
  EXPECT_NEAR(misfit(log_errors({200, 20}, target), {1, 3}), 4 * std::pow(std::log(2.0), 2), 1e-12);
  EXPECT_TRUE(within_tolerance({101.9, 9.81}, target, 0.02));
  EXPECT_FALSE(within_tolerance({101.9, 9.79}, target, 0.02));
}

}  // namespace
}  // namespace rockcal::calibration
