// The driver against synthetic models: recovery, compromise, noise, failures, strategy choice.
#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "orchestrator/calibration/driver.hpp"
#include "orchestrator/calibration/run_faults.hpp"
#include "orchestrator/calibration/sentence.hpp"
#include "synthetic.hpp"

namespace rockcal::calibration {
namespace {

using testing::ModelEvaluator;

struct Recovery {
  CalibrationReport report;
  int evaluations;
};

Recovery calibrate(testing::Model model, BondPoint truth, const nlohmann::json& overrides = {},
                   double noise = 0.0, double failure_rate = 0.0) {
  const CalibrationCampaign c = testing::campaign(model(truth), overrides);
  ModelEvaluator evaluator(model);
  evaluator.noise = noise;
  evaluator.failure_rate = failure_rate;
  CalibrationReport report = run_calibration(c, evaluator);
  // The search's own evaluations: the consistent-set trace after it has a budget of its own.
  return {report, int(report.history.size()) - report.trace.evaluations};
}

void expect_recovered(const Recovery& r, BondPoint truth, const PeakLoads& targets) {
  ASSERT_TRUE(r.report.best.has_value());
  const EvaluationRecord& best = *r.report.best;
  EXPECT_EQ(r.report.verdict, Verdict::feasible) << r.report.verdict_reason;
  EXPECT_EQ(r.report.stop_reason, StopReason::tolerance_met);
  EXPECT_NEAR(best.point.fr0_n / truth.fr0_n, 1.0, 0.10);
  EXPECT_NEAR(best.point.fs0_n / truth.fs0_n, 1.0, 0.10);
  EXPECT_NEAR(best.loads->uct_n / targets.uct_n, 1.0, 0.02);
  EXPECT_NEAR(best.loads->btt_n / targets.btt_n, 1.0, 0.02);
  EXPECT_LE(r.evaluations, 40);
}

TEST(Driver, HomogeneousModelUsesRatioThenScaleAndRecoversTruth) {
  for (BondPoint truth :
       {BondPoint{40, 90}, BondPoint{64, 64}, BondPoint{5, 300}, BondPoint{500, 20}}) {
    const Recovery r = calibrate(testing::power_law, truth);
    expect_recovered(r, truth, testing::power_law(truth));
    EXPECT_TRUE(r.report.homogeneity.holds());
    EXPECT_NEAR(r.report.homogeneity.checks.front().exponent_uct, 1.0, 1e-9);
    // (64, 64) is met within 2% by the start batch itself (its probe point is 63.2, 63.2).
    EXPECT_EQ(r.report.strategy_used, truth.fr0_n == 64 ? "none" : "ratio_scale");
    RecordProperty("evaluations_power_law_" + std::to_string(int(truth.fr0_n)), r.evaluations);
    std::printf("power law truth (%g, %g): %d evaluations\n", truth.fr0_n, truth.fs0_n,
                r.evaluations);
  }
}

TEST(Driver, BoundedRatioModelRecoversTruthInsideItsRange) {
  const BondPoint truth{50, 70};
  const Recovery r = calibrate(testing::smooth_min, truth);
  expect_recovered(r, truth, testing::smooth_min(truth));
  EXPECT_EQ(r.report.strategy_used, "ratio_scale");
  std::printf("smooth-min truth (50, 70): %d evaluations\n", r.evaluations);
}

TEST(Driver, NonHomogeneousModelFallsBackTo2dSearch) {
  for (const char* algorithm : {"bobyqa", "sbplx"}) {
    const BondPoint truth{40, 90};
    const Recovery r = calibrate(testing::non_homogeneous, truth, {{"algorithm", algorithm}});
    EXPECT_FALSE(r.report.homogeneity.holds());
    EXPECT_EQ(r.report.strategy_used, "direct_2d");
    expect_recovered(r, truth, testing::non_homogeneous(truth));
    std::printf("non-homogeneous, %s: %d evaluations\n", algorithm, r.evaluations);
  }
}

TEST(Driver, NoisyModelStillMeetsTolerance) {
  const BondPoint truth{40, 90};
  const Recovery r = calibrate(testing::power_law, truth, {}, 0.005);
  expect_recovered(r, truth, testing::power_law(truth));
  std::printf("power law with 0.5%% noise: %d evaluations\n", r.evaluations);
}

TEST(Driver, FailedEvaluationsArePenalisedNotFatal) {
  const BondPoint truth{40, 90};
  const Recovery r = calibrate(testing::power_law, truth, {}, 0.0, 0.2);
  int failed = 0;
  for (const EvaluationRecord& e : r.report.history) {
    if (!e.loads) {
      ++failed;
      EXPECT_TRUE(std::isfinite(e.misfit));
      EXPECT_FALSE(e.error.empty());
    }
  }
  EXPECT_GT(failed, 0);
  expect_recovered(r, truth, testing::power_law(truth));
  std::printf("power law with 20%% failures: %d evaluations, %d failed\n", r.evaluations, failed);
}

TEST(Driver, UnreachableRatioGivesCompromiseWithRatioRange) {
  // The smooth-min model's UCT/BTT ratio stays within [5.95, 23.8]; ask for 3.
  const CalibrationCampaign c = testing::campaign({60000, 20000});
  ModelEvaluator evaluator(testing::smooth_min);
  const CalibrationReport r = run_calibration(c, evaluator);
  EXPECT_EQ(r.verdict, Verdict::compromise);
  ASSERT_TRUE(r.ratio.has_value());
  EXPECT_FALSE(r.ratio->target_inside());
  EXPECT_DOUBLE_EQ(r.ratio->target, 3.0);
  EXPECT_GT(r.ratio->min, 5.9);
  EXPECT_LT(r.ratio->min, 6.5);  // the search found the low end of the reachable ratios
  EXPECT_NE(r.verdict_reason.find("outside"), std::string::npos);
  EXPECT_LE(r.history.size(), 40u);
  // The compromise splits the log error between both loads (equal weights): UCT too high, BTT low.
  const LogErrors e = log_errors(*r.best->loads, c.targets.model_loads_n);
  EXPECT_GT(e.uct, 0.0);
  EXPECT_LT(e.btt, 0.0);
  EXPECT_NEAR(e.uct, -e.btt, 0.05);
  std::printf("unreachable ratio: %zu evaluations, ratio range [%g, %g]\n", r.history.size(),
              r.ratio->min, r.ratio->max);
}

TEST(Driver, ABestPointOnTheBoundsNamesTheBoundsAndTheRunsWithoutAPeakWithTheirFixes) {
  // The truth (3000, 3000) lies beyond the bounds [1, 1000] at a reachable ratio: the search ends
  // on the upper bounds, with a fifth of its points failing as runs without a peak.
  const CalibrationCampaign c = testing::campaign(
      testing::power_law({3000, 3000}), {{"consistency_evaluations", 0}, {"suggest", false}});
  ModelEvaluator evaluator(testing::power_law);
  evaluator.failure_rate = 0.2;
  evaluator.failure_error =
      "no peak: the load did not fall past a peak with bonds breaking before loading.max_strain";
  const CalibrationReport r = run_calibration(c, evaluator);
  ASSERT_TRUE(r.best.has_value());
  EXPECT_EQ(r.verdict, Verdict::compromise);
  int failed = 0;
  for (const EvaluationRecord& e : r.history) failed += e.loads ? 0 : 1;
  ASSERT_GT(failed, 0);
  // Each failed point is a UCT and a BTT run without a peak.
  EXPECT_EQ(r.verdict_reason,
            sentence("the loads are not both within 2%%: the best point lies on the search's "
                     "bounds: F_r0 = %.4g N lies on its upper bound 1000 (widen \"bounds.fr0\" "
                     "above 1000); ",
                     r.best->point.fr0_n) +
                sentence("F_s0 = %.4g N lies on its upper bound 1000 (widen \"bounds.fs0\" above "
                         "1000); ",
                         r.best->point.fs0_n) +
                sentence("%.0f of %.0f runs ended without a peak and count as failed (%.0f at "
                         "loading.max_strain: raise it in the job template so that they reach "
                         "one)",
                         2 * failed, 2 * double(r.history.size()), 2 * failed));
  EXPECT_EQ(r.verdict_reason.find("budget"), std::string::npos);
}

// Runs that ended still loading up past the bond-controlled window (the engine's auto speed) are
// counted apart from those stopped by a limit the user can raise: there is nothing to raise.
TEST(Driver, RunsStillRisingPastTheWindowAreNamedAsSuchAmongThoseWithoutAPeak) {
  std::vector<EvaluationRecord> history(4);
  history[0].error =
      "no peak: the load was still rising past the bond-controlled window (loading.past_window "
      "\"stop\"): no peak set by the bond strengths; largest load 7 N with 40 bonds broken";
  history[1].error = history[0].error;
  history[2].error =
      "no peak: the load did not fall past a peak with bonds breaking before loading.max_strain";
  history[3].loads = PeakLoads{1.0, 1.0};
  EXPECT_EQ(no_peak_text(history),
            "3 of 4 runs ended without a peak and count as failed (1 at loading.max_strain: raise "
            "it in the job template so that they reach one; 2 still loading up past the "
            "bond-controlled window: no peak set by the bond strengths there)");
  history[2] = history[3];
  EXPECT_EQ(no_peak_text(history),
            "2 of 4 runs ended without a peak and count as failed (2 still loading up past the "
            "bond-controlled window: no peak set by the bond strengths there)");
}

TEST(Driver, BudgetIsRespected) {
  const CalibrationCampaign c =
      testing::campaign({60000, 20000}, {{"max_evaluations", 9}, {"strategy", "direct_2d"}});
  ModelEvaluator evaluator(testing::smooth_min);
  const CalibrationReport r = run_calibration(c, evaluator);
  EXPECT_EQ(r.history.size(), 9u);
  EXPECT_EQ(r.stop_reason, StopReason::budget_exhausted);
  EXPECT_EQ(evaluator.requests, 9);
}

TEST(Driver, GlobalAlgorithmStaysInBoundsAndFindsTarget) {
  const BondPoint truth{40, 90};
  const Recovery r = calibrate(testing::non_homogeneous, truth,
                               {{"algorithm", "direct_l"}, {"max_evaluations", 200}});
  for (const EvaluationRecord& e : r.report.history) {
    EXPECT_GE(e.point.fr0_n, 1.0);
    EXPECT_LE(e.point.fr0_n, 1000.0);
    EXPECT_GE(e.point.fs0_n, 1.0);
    EXPECT_LE(e.point.fs0_n, 1000.0);
  }
  EXPECT_EQ(r.report.verdict, Verdict::feasible);
  std::printf("non-homogeneous, direct_l: %d evaluations\n", r.evaluations);
}

TEST(Driver, SeedScatterReRunsTheBestPoint) {
  const BondPoint truth{40, 90};
  const CalibrationCampaign c =
      testing::campaign(testing::power_law(truth), {{"seeds", {2, 3, 4}}});
  ModelEvaluator evaluator(testing::power_law);
  evaluator.noise = 0.01;
  const CalibrationReport r = run_calibration(c, evaluator);
  ASSERT_EQ(r.scatter.runs.size(), 4u);
  EXPECT_EQ(r.scatter.runs[0].seed, c.sample_seed);
  EXPECT_EQ(r.scatter.runs[3].seed, 4u);
  for (const ScatterRun& s : r.scatter.runs) {
    EXPECT_EQ(evaluator.log.back().point, r.best->point);
    EXPECT_TRUE(s.loads.has_value());
  }
  ASSERT_TRUE(r.scatter.uct.has_value());
  EXPECT_EQ(r.scatter.uct->runs, 4);
  EXPECT_GT(r.scatter.uct->stddev_n, 0.0);
  EXPECT_LT(r.scatter.uct->stddev_n / r.scatter.uct->mean_n, 0.02);
  // The scatter is not charged to the search budget.
  EXPECT_EQ(evaluator.requests, int(r.history.size()) + 3);
}

TEST(Driver, CancelFromAnotherThreadReturnsPartialReport) {
  const CalibrationCampaign c =
      testing::campaign({60000, 20000}, {{"max_evaluations", 400}, {"strategy", "direct_2d"}});
  struct Slow : ModelEvaluator {
    using ModelEvaluator::ModelEvaluator;
    std::vector<EvaluationOutcome> evaluate_batch(std::span<const EvaluationRequest> r) override {
      std::this_thread::sleep_for(std::chrono::milliseconds(3));
      return ModelEvaluator::evaluate_batch(r);
    }
  } evaluator(testing::smooth_min);
  CalibrationThread run(c, evaluator);
  while (evaluator.requests < 10) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  run.cancel();
  const CalibrationReport r = run.wait();
  EXPECT_EQ(r.stop_reason, StopReason::cancelled);
  EXPECT_EQ(r.verdict, Verdict::incomplete);
  EXPECT_GE(r.history.size(), 10u);
  EXPECT_LT(r.history.size(), 400u);
}

TEST(Driver, EvaluatorCancellationStopsTheSearch) {
  ModelEvaluator model(testing::power_law);
  testing::CachingEvaluator evaluator(model);
  evaluator.cancel_after = 5;
  const CalibrationReport r = run_calibration(testing::campaign({60000, 20000}), evaluator);
  EXPECT_EQ(r.stop_reason, StopReason::cancelled);
  EXPECT_LE(r.history.size(), 5u);
}

}  // namespace
}  // namespace rockcal::calibration
