// Focus: the check runs at a bayes calibration's estimate judge its prediction. Their mean is
// compared with the predicted mean within the spread the emulator's variance and the packings'
// scatter allow that mean; a check outside it turns "feasible" into a compromise naming it, so the
// summary never says "feasible" on the emulators' word alone when real runs say otherwise. A check
// that differs from the prediction yet meets the targets itself (a noiseless engine, whose interval
// is tiny) leaves "feasible" standing and is named beside it.
#include <gtest/gtest.h>

#include <cmath>

#include "orchestrator/calibration/bayes/check.hpp"
#include "orchestrator/calibration/bayes/verdict.hpp"
#include "orchestrator/calibration/report.hpp"
#include "synthetic.hpp"

namespace rockcal::calibration {
namespace {

orch::Ensemble runs(std::initializer_list<double> loads) {
  std::vector<orch::Realisation> rs;
  std::uint64_t seed = 1;
  for (double l : loads) rs.push_back({seed++, 0, "succeeded", l, {}, {}, ""});
  return orch::make_ensemble(rs);
}

PredictedLoad prediction(double target, double mean) {
  PredictedLoad p;
  p.target_n = target;
  p.mean_n = mean;
  p.relative_error = mean / target - 1.0;
  p.emulator_sd = 0.03;
  p.run_sd = 0.132;
  return p;
}

TEST(CheckRuns, TheirMeanIsJudgedAgainstTheSpreadThePredictionAllowsIt) {
  // Two packings 8% and 11% below a prediction on target: sd of their ln mean
  // sqrt(0.03^2 + 0.132^2 / 2) = 0.098041; z = ln(sqrt(0.92 * 0.89)) / 0.098041 = -1.01955.
  const std::optional<CheckAgreement> a =
      check_agreement(prediction(100.0, 100.0), runs({92.0, 89.0}));
  ASSERT_TRUE(a);
  EXPECT_EQ(a->n, 2);
  EXPECT_NEAR(a->mean_n, std::sqrt(92.0 * 89.0), 1e-9);
  EXPECT_NEAR(a->sd, 0.098041, 1e-6);
  EXPECT_NEAR(a->z, -1.01955, 1e-5);
  EXPECT_NEAR(a->relative_to_target, std::sqrt(92.0 * 89.0) / 100.0 - 1.0, 1e-12);
  EXPECT_TRUE(a->agrees);
  // 30% low on both packings: z = ln(0.7) / 0.098041 = -3.64, beyond the 99% quantile 2.576.
  const std::optional<CheckAgreement> low =
      check_agreement(prediction(100.0, 100.0), runs({70.0, 70.0}));
  ASSERT_TRUE(low);
  EXPECT_FALSE(low->agrees);
  // Failed check runs leave nothing to judge.
  std::vector<orch::Realisation> failed = {{1, 0, "failed", {}, {}, {}, "no peak"}};
  EXPECT_FALSE(check_agreement(prediction(100.0, 100.0), orch::make_ensemble(failed)));
}

CalibrationReport report_with(const CalibrationCampaign& c, double uct_check, double btt_check) {
  CalibrationReport r;
  r.stop_reason = StopReason::answered;
  PosteriorSummary p;
  p.uct = prediction(c.targets.model_loads_n.uct_n, c.targets.model_loads_n.uct_n * 1.001);
  p.btt = prediction(c.targets.model_loads_n.btt_n, c.targets.model_loads_n.btt_n * 0.999);
  p.fr0 = {30, 40};
  p.fs0 = {60, 70};
  p.runs = 75;
  p.points = 39;
  p.unique = true;
  p.why = "the region is narrow";
  p.uct.check = check_agreement(p.uct, runs({p.uct.mean_n * uct_check, p.uct.mean_n * uct_check}));
  p.btt.check = check_agreement(p.btt, runs({p.btt.mean_n * btt_check, p.btt.mean_n * btt_check}));
  r.posterior = p;
  return r;
}

TEST(CheckRuns, ChecksThatDisagreeTurnAFeasiblePredictionIntoACompromiseNamingThem) {
  const CalibrationCampaign c =
      testing::campaign({120000, 9000}, {{"strategy", "bayes"}, {"max_evaluations", 100}});
  CalibrationReport agree = report_with(c, 0.9, 1.05);
  judge_posterior(agree, c);
  EXPECT_EQ(agree.verdict, Verdict::feasible) << agree.verdict_reason;

  CalibrationReport disagree = report_with(c, 0.7, 1.05);
  judge_posterior(disagree, c);
  EXPECT_EQ(disagree.verdict, Verdict::compromise);
  EXPECT_NE(disagree.verdict_reason.find(
                "but the check runs there disagree with the prediction beyond the packings' "
                "scatter and the emulators' variance (UCT -30% (z -3.6) from the prediction, "
                "outside its 99% interval): the emulators are wrong near the estimate"),
            std::string::npos)
      << disagree.verdict_reason;
  EXPECT_EQ(disagree.verdict_reason.find("BTT +5%"), std::string::npos) << disagree.verdict_reason;
  EXPECT_NE(disagree.verdict_reason.find("(a larger \"max_evaluations\") would correct them"),
            std::string::npos);
  // On a fine posterior it is the fine runs that would correct them.
  CalibrationReport fine = report_with(c, 0.7, 1.05);
  fine.posterior->resolution = "fine";
  judge_posterior(fine, c);
  EXPECT_NE(
      fine.verdict_reason.find("(a larger \"fidelity\".\"runs\": fine runs) would correct them"),
      std::string::npos)
      << fine.verdict_reason;
  // The JSON carries the figures the sentence quotes.
  const nlohmann::json j = to_json(disagree, c);
  const nlohmann::json& k = j["posterior"]["uct"]["check"];
  EXPECT_EQ(k["agrees"], false);
  EXPECT_EQ(k["runs"], 2);
  EXPECT_NEAR(k["z"].get<double>(), std::log(0.7) / 0.098041, 1e-4);
  EXPECT_EQ(j["posterior"]["btt"]["check"]["agrees"], true);
}

TEST(CheckRuns, AChecksDifferenceThatStillMeetsTheTargetsLeavesFeasibleAndIsNamed) {
  const CalibrationCampaign c =
      testing::campaign({120000, 9000}, {{"strategy", "bayes"}, {"max_evaluations", 100}});
  CalibrationReport r = report_with(c, 0.995, 1.0);
  // A noiseless engine: the prediction allows its check mean next to nothing.
  for (PredictedLoad* l : {&r.posterior->uct, &r.posterior->btt}) {
    l->emulator_sd = 1e-4;
    l->run_sd = 0.0;
    l->check = check_agreement(*l, runs({l->mean_n * (l == &r.posterior->uct ? 0.995 : 1.0)}));
  }
  ASSERT_FALSE(r.posterior->uct.check->agrees);
  judge_posterior(r, c);
  EXPECT_EQ(r.verdict, Verdict::feasible) << r.verdict_reason;
  EXPECT_NE(r.verdict_reason.find("; the check runs at the estimate differ from the prediction "
                                  "beyond its 99% interval (UCT -0.5% (z -50), itself -0.401% of "
                                  "the target) but meet the targets themselves"),
            std::string::npos)
      << r.verdict_reason;
  // Without scatter between packings nothing is said of it.
  EXPECT_EQ(r.verdict_reason.find("scatters"), std::string::npos) << r.verdict_reason;
}

// Fitted on the check runs too, the posterior can move its estimate away from the point they ran
// at (the seed rock at D/R 49: checks at (59.58, 39.47), the estimate after them (41.62, 43.39)).
// The report then says where the checks ran and that the estimate has no run of its own; an
// estimate that stayed says nothing of the kind.
TEST(CheckRuns, AnEstimateThatMovedAfterTheChecksIsSaidToRestOnTheEmulatorsAlone) {
  const CalibrationCampaign c =
      testing::campaign({120000, 9000}, {{"strategy", "bayes"}, {"max_evaluations", 100}});
  CalibrationReport stayed = report_with(c, 0.9, 1.05);
  stayed.posterior->estimate = {40.0, 60.0};
  stayed.posterior->checked_at = BondPoint{40.2, 59.9};
  judge_posterior(stayed, c);
  EXPECT_FALSE(stayed.posterior->estimate_moved());
  EXPECT_EQ(stayed.verdict_reason.find("check runs were made at"), std::string::npos)
      << stayed.verdict_reason;

  CalibrationReport moved = report_with(c, 0.85, 1.16);
  moved.posterior->estimate = {41.62, 43.39};
  moved.posterior->checked_at = BondPoint{59.58, 39.47};
  judge_posterior(moved, c);
  EXPECT_TRUE(moved.posterior->estimate_moved());
  EXPECT_NE(
      moved.verdict_reason.find(
          "; the check runs were made at (F_r0 59.58, F_s0 39.47), the estimate before them "
          "(UCT -14.9%, BTT +15.9% of the targets); fitted on them too, the posterior moved its "
          "estimate to (41.62, 43.39), where no run has been made: its predicted loads rest "
          "on the emulators alone"),
      std::string::npos)
      << moved.verdict_reason;
  const nlohmann::json j = to_json(moved, c);
  EXPECT_EQ(j["posterior"]["estimate_moved_after_check"], true);
  EXPECT_EQ(j["posterior"]["checked_at"]["fr0"], 59.58);
  EXPECT_EQ(to_json(stayed, c)["posterior"]["estimate_moved_after_check"], false);
}

// Check runs that gave no loads (the estimate's UCT without a peak) bear nothing out: a prediction
// that meets the targets is no answer there, and the report says where they ran and why.
TEST(CheckRuns, ChecksWithoutLoadsTurnAFeasiblePredictionIntoACompromiseSayingWhy) {
  const CalibrationCampaign c =
      testing::campaign({120000, 9000}, {{"strategy", "bayes"}, {"max_evaluations", 100}});
  CalibrationReport r = report_with(c, 1.0, 1.0);
  r.posterior->uct.check.reset();
  r.posterior->btt.check.reset();
  r.posterior->estimate = {35.55, 52.36};
  r.posterior->checked_at = BondPoint{34.62, 52.93};
  r.posterior->check_failed = "uct: no peak: the load was still rising past the window";
  judge_posterior(r, c);
  EXPECT_EQ(r.verdict, Verdict::compromise);
  EXPECT_EQ(r.verdict_reason.rfind(
                "the predicted loads at the estimate meet the targets (UCT +0.1%, BTT -0.1%), but "
                "the check runs at (F_r0 34.62, F_s0 52.93) gave no loads (uct: no peak: the load "
                "was still rising past the window): no run bears the prediction out there; the "
                "estimate then moved to (35.55, 52.36): the estimate lies at the edge of "
                "strengths without a peak",
                0),
            0u)
      << r.verdict_reason;
  EXPECT_EQ(r.verdict_reason.find("check runs were made at"), std::string::npos);
  EXPECT_EQ(to_json(r, c)["posterior"]["check_failed"],
            "uct: no peak: the load was still rising past the window");
  // A check that failed for another reason (a crashed job) is said, with no cause read into it.
  r.posterior->check_failed = "uct: the engine exited with status 134";
  judge_posterior(r, c);
  EXPECT_EQ(r.verdict, Verdict::compromise);
  EXPECT_NE(r.verdict_reason.find("gave no loads (uct: the engine exited with status 134)"),
            std::string::npos)
      << r.verdict_reason;
  EXPECT_EQ(r.verdict_reason.find("without a peak"), std::string::npos) << r.verdict_reason;
  CalibrationReport fine = report_with(c, 1.0, 1.0);
  EXPECT_TRUE(to_json(fine, c)["posterior"]["check_failed"].is_null());
}

// A region that reaches a bound only because it is wide (a few fine runs on it) does not press on
// the bound: the estimate lies inside, the miss is the emulators' (the D/R 49 case: "widen bounds"
// named as the cause with the estimate at F_r0 29 of a box up to 1666). An estimate at the bound
// does press on it.
TEST(CheckRuns, ARegionThatReachesABoundOnlyByItsWidthDoesNotPressOnIt) {
  const CalibrationCampaign c =
      testing::campaign({120000, 9000}, {{"strategy", "bayes"}, {"max_evaluations", 100}});
  CalibrationReport r = report_with(c, 1.0, 1.0);
  r.stop_reason = StopReason::budget_exhausted;
  PosteriorSummary& p = *r.posterior;
  p.uct.check.reset();
  p.btt.check.reset();
  p.btt.relative_error = -0.0239;
  p.unique = false;
  p.grid_cells = 81;
  p.box_fr0 = p.grid_fr0 = {1, 1000};
  p.box_fs0 = p.grid_fs0 = {1, 1000};
  p.estimate = {29.42, 39.7};
  p.bounds_reached = {"the upper bound of F_r0 (1000)"};
  judge_posterior(r, c);
  EXPECT_EQ(r.verdict, Verdict::compromise);
  EXPECT_EQ(r.verdict_reason.find("presses on"), std::string::npos) << r.verdict_reason;
  EXPECT_NE(
      r.verdict_reason.find(" when the budget of 100 runs ran out, with the emulators holding"),
      std::string::npos)
      << r.verdict_reason;
  EXPECT_NE(r.verdict_reason.find("(the region reaches the upper bound of F_r0 (1000), though the "
                                  "estimate lies inside)"),
            std::string::npos)
      << r.verdict_reason;
  p.estimate = {980, 39.7};  // within two cells (a factor 1000^(2/81) = 1.19) of the bound
  judge_posterior(r, c);
  EXPECT_NE(r.verdict_reason.find(": the posterior presses on the upper bound of F_r0 (1000); the "
                                  "targets need strengths beyond it: widen \"bounds\""),
            std::string::npos)
      << r.verdict_reason;
}

}  // namespace
}  // namespace rockcal::calibration
