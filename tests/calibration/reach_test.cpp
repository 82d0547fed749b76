// Focus: the interaction range as the calibration's third parameter ("reach", reach.hpp) on a
// formula engine whose UCT/BTT load ratio range depends on the range in the patched template:
// a ratio reached only at the second range moves the calibration there and meets the targets, a
// ratio reached at the first stays there with no extra run, a ratio no range reaches is a
// compromise naming every range tried, the stiffness stage is redone at the new range, the bayes
// search decides to leave a range once, and bad fields are refused naming them.
#include <gtest/gtest.h>

#include "orchestrator/calibration/bayes/search.hpp"
#include "orchestrator/calibration/driver.hpp"
#include "orchestrator/calibration/reach.hpp"
#include "orchestrator/calibration/report.hpp"
#include "orchestrator/calibration/sentence.hpp"
#include "orchestrator/calibration/stiffness.hpp"
#include "synthetic.hpp"

namespace rockcal::calibration {
namespace {

using nlohmann::json;

// The range factor the evaluator's template runs at (1 without the effect).
double range_of(const testing::ModelEvaluator& e) {
  const json::json_pointer at("/effects/interaction_range/factor");
  return e.template_patch.contains(at) ? e.template_patch.at(at).get<double>() : 1.0;
}

// smooth_min's loads (UCT/BTT within [5.95, 23.8]) with the UCT x (2 x range - 1): at range 1.5
// the ratios reached are [11.9, 47.6].
PeakLoads ranged(const BondPoint& p, double range) {
  PeakLoads l = testing::smooth_min(p);
  l.uct_n *= 2 * range - 1;
  return l;
}

struct RangedEvaluator : testing::ModelEvaluator {
  RangedEvaluator() : testing::ModelEvaluator(nullptr) {
    model = [this](const BondPoint& p) { return ranged(p, range_of(*this)); };
  }
};

const json kReach = {{"reach", {{"interaction_range", {1, 1.5}}}}};

std::string ratio_text(const ReachAttempt& a) {
  return sentence("range %.3g: [%.4g, %.4g] over ", a.interaction_range, a.ratio->min,
                  a.ratio->max) +
         sentence("%.0f runs", double(a.history.size()));
}

// Strengths whose loads at range 1.5 have a UCT/BTT ratio (41.3) that range 1 does not reach.
constexpr BondPoint kTruth{200, 60};

CalibrationCampaign beyond_range_1(const json& overrides = json::object()) {
  json o = kReach;
  o.merge_patch(overrides);
  return testing::campaign(ranged(kTruth, 1.5), o);
}

TEST(Reach, ARatioReachedOnlyAtTheSecondRangeMovesThereAndMeetsTheTargets) {
  const BondPoint truth = kTruth;
  const PeakLoads targets = ranged(truth, 1.5);
  ASSERT_GT(targets.uct_n / targets.btt_n, 23.8);  // out of range 1's reach
  const CalibrationCampaign c = beyond_range_1();
  RangedEvaluator e;
  const CalibrationReport r = run_calibration(c, e);
  ASSERT_TRUE(r.reach);
  ASSERT_EQ(r.reach->tried.size(), 2u);
  const ReachAttempt& first = r.reach->tried[0];
  const ReachAttempt& second = r.reach->tried[1];
  EXPECT_EQ(first.interaction_range, 1.0);
  EXPECT_EQ(second.interaction_range, 1.5);
  ASSERT_TRUE(first.ratio && second.ratio);
  EXPECT_FALSE(first.ratio->target_inside());
  EXPECT_LE(first.ratio->max, 23.81);
  EXPECT_TRUE(second.ratio->target_inside());
  // Every run after the move ran at 1.5, within the budget left by range 1.
  EXPECT_EQ(e.template_patch, json::parse(R"({"effects":{"interaction_range":{"factor":1.5}}})"));
  EXPECT_EQ(second.history.size(), r.history.size());
  EXPECT_LE(first.history.size() + r.history.size() - r.trace.evaluations, 40u);
  EXPECT_EQ(r.verdict, Verdict::feasible) << r.verdict_reason;
  ASSERT_TRUE(r.best);
  EXPECT_NEAR(r.best->point.fr0_n / truth.fr0_n, 1.0, 0.1);
  EXPECT_NEAR(r.best->point.fs0_n / truth.fs0_n, 1.0, 0.1);
  const std::string why =
      sentence(
          "interaction range 1.5: the target UCT/BTT load ratio %.4g lay outside the ratios the "
          "runs reached at the ranges before it, inside this one's (",
          targets.uct_n / targets.btt_n) +
      ratio_text(first) + "; " + ratio_text(second) + ")";
  EXPECT_EQ(r.reach->why, why);
  EXPECT_EQ(r.verdict_reason.rfind("at interaction range 1.5, the last tried: both peak loads "
                                   "within 2% of their targets",
                                   0),
            0u)
      << r.verdict_reason;
  EXPECT_NE(r.verdict_reason.find(". Reach: " + why), std::string::npos) << r.verdict_reason;

  const json j = to_json(r, c);
  EXPECT_EQ(j["reach"]["interaction_range"], 1.5);
  EXPECT_EQ(j["reach"]["listed"], json({1, 1.5}));
  EXPECT_EQ(j["reach"]["tried"][0]["ratio"]["target_inside"], false);
  EXPECT_EQ(j["reach"]["tried"][0]["runs"], first.history.size());
  EXPECT_EQ(j["reach"]["tried"][0]["history"].size(), first.history.size());
  EXPECT_EQ(j["reach"]["why"], why);
  EXPECT_EQ(j["evaluations"], first.history.size() + r.history.size());
  std::printf("%s\nmoved to 1.5 after %zu runs at 1; %zu runs at 1.5\n", r.verdict_reason.c_str(),
              first.history.size(), r.history.size());
}

TEST(Reach, ARatioReachedAtTheFirstRangeStaysThereWithNoExtraRun) {
  const PeakLoads targets = ranged({50, 70}, 1.0);
  RangedEvaluator with_reach, without;
  const CalibrationReport r = run_calibration(testing::campaign(targets, kReach), with_reach);
  const CalibrationReport plain = run_calibration(testing::campaign(targets), without);
  EXPECT_EQ(r.verdict, Verdict::feasible) << r.verdict_reason;
  ASSERT_TRUE(r.reach);
  ASSERT_EQ(r.reach->tried.size(), 1u);
  EXPECT_EQ(with_reach.template_patch,
            json::parse(R"({"effects":{"interaction_range":{"factor":1}}})"));
  EXPECT_EQ(with_reach.log.size(), without.log.size());
  EXPECT_EQ(r.history.size(), plain.history.size());
  EXPECT_EQ(
      r.reach->why,
      sentence("interaction range 1, the first listed: its runs reached the target UCT/BTT load "
               "ratio %.4g (",
               targets.uct_n / targets.btt_n) +
          ratio_text(r.reach->tried[0]) + ")");
}

TEST(Reach, ARatioNoRangeReachesIsACompromiseNamingEveryRangeTried) {
  const PeakLoads targets{60000, 1000};  // ratio 60, beyond 47.6
  const CalibrationCampaign c = testing::campaign(targets, kReach);
  RangedEvaluator e;
  const CalibrationReport r = run_calibration(c, e);
  EXPECT_EQ(r.verdict, Verdict::compromise);
  ASSERT_TRUE(r.reach);
  ASSERT_EQ(r.reach->tried.size(), 2u);
  ASSERT_TRUE(r.ratio);
  EXPECT_FALSE(r.ratio->target_inside());
  const std::string why = "no interaction range tried reaches the target UCT/BTT load ratio 60 (" +
                          ratio_text(r.reach->tried[0]) + "; " + ratio_text(r.reach->tried[1]) +
                          ")";
  EXPECT_EQ(r.reach->why, why);
  // Today's ratio-out-of-reach reason (the last range's ratios), then every range tried.
  EXPECT_EQ(r.verdict_reason.rfind("at interaction range 1.5, the last tried: the target UCT/BTT "
                                   "load ratio 60 lies outside the range",
                                   0),
            0u)
      << r.verdict_reason;
  EXPECT_NE(r.verdict_reason.find(". Reach: " + why), std::string::npos) << r.verdict_reason;
}

TEST(Reach, ABudgetSpentAtTheFirstRangeSaysTheNextWasNotTried) {
  // direct_2d at range 1 spends the whole budget: the ratio is still out of reach, 1.5 untried.
  const CalibrationCampaign c =
      beyond_range_1({{"strategy", "direct_2d"}, {"max_evaluations", 12}});
  RangedEvaluator e;
  const CalibrationReport r = run_calibration(c, e);
  ASSERT_TRUE(r.reach);
  ASSERT_EQ(r.reach->tried.size(), 1u);
  EXPECT_EQ(r.verdict, Verdict::compromise);
  const std::string tail =
      sentence("; range 1.5 not tried: %.0f evaluations of the budget were left, fewer than 4",
               double(r.reach->evaluations_left));
  EXPECT_LT(r.reach->evaluations_left, 4);
  EXPECT_EQ(r.reach->why.substr(r.reach->why.size() - tail.size()), tail) << r.reach->why;
}

// Measured on the engine at D/R 8: range 1.5's runs can all end without a peak (the load still
// rising past the bond-controlled window). The reason says so for that range, and the verdict,
// the last range's, says which range it is.
TEST(Reach, ARangeWhoseRunsAllFailSaysWhyAndTheVerdictNamesTheRange) {
  struct NoPeakBeyondRange1 : RangedEvaluator {
    std::vector<EvaluationOutcome> evaluate_batch(
        std::span<const EvaluationRequest> requests) override {
      failure_rate = range_of(*this) > 1 ? 1.0 : 0.0;
      return RangedEvaluator::evaluate_batch(requests);
    }
  } e;
  e.failure_error =
      "no peak: the load was still rising past the bond-controlled window "
      "(loading.past_window \"stop\")";
  const CalibrationReport r = run_calibration(beyond_range_1(), e);
  ASSERT_EQ(r.reach ? r.reach->tried.size() : 0u, 2u);
  EXPECT_EQ(r.verdict, Verdict::failed);
  const std::size_t n = r.history.size();
  ASSERT_GE(n, 4u);
  const std::string why =
      "no interaction range tried reaches the target UCT/BTT load ratio 41.29 (" +
      ratio_text(r.reach->tried[0]) +
      sentence(
          "; range 1.5: no run gave both loads (%.0f evaluations; %.0f of %.0f runs ended "
          "without a peak and count as failed",
          double(n), double(2 * n), double(2 * n)) +
      sentence(
          " (%.0f still loading up past the bond-controlled window: no peak set by the "
          "bond strengths there)))",
          double(2 * n));
  EXPECT_EQ(r.reach->why, why);
  EXPECT_EQ(r.verdict_reason,
            "at interaction range 1.5, the last tried: no evaluation succeeded. Reach: " + why);
}

// The range multiplies E at a given K_r (docs/reach.md): E = 0.3 K_r (2 x range - 1).
TEST(Reach, WithAnETargetTheStiffnessStageIsRedoneAtTheNewRange) {
  const CalibrationCampaign c = beyond_range_1({{"targets", {{"youngs_modulus", 6000}}}});
  RangedEvaluator e;
  e.elastic_model = [&e](const ProbeRequest& p, std::uint64_t) {
    const double kr = p.patch.at("material").at("kr").get<double>();
    return testing::ElasticConstants{0.3 * kr * (2 * range_of(e) - 1), 0.2};
  };
  const CalibrationReport r = run_calibration(c, e);
  ASSERT_TRUE(r.reach && r.stiffness);
  ASSERT_EQ(r.reach->tried.size(), 2u);
  // At 1.5 the same E needs half range 1's K_r: 6000 / (0.3 x 2).
  EXPECT_NEAR(r.stiffness->kr_n_m, 10000, 1e-6);
  ASSERT_TRUE(r.stiffness->youngs_modulus_pa);
  EXPECT_NEAR(*r.stiffness->youngs_modulus_pa, 6000, 1e-6);
  EXPECT_EQ(range_of(e), 1.5);
  EXPECT_EQ(e.template_patch["material"]["kr"], 10000);
}

// The bayes strategy, which would spend the whole budget at a range, leaves it once a quarter of
// the budget (reach_probe_runs) has shown the ratio out of reach: the runs then in flight (two
// batches of the two workers) are all it adds, and the rest goes to the next range.
TEST(Reach, TheBayesStrategyLeavesARangeOnceItsRunsShowTheRatioOutOfReach) {
  const json noisy_bayes = {{"strategy", "bayes"}, {"max_evaluations", 100}};
  // Range 1 alone: the noisy runs keep the search going past a quarter of the budget.
  RangedEvaluator alone;
  alone.noise = 0.1;
  json only_1 = noisy_bayes;
  only_1["reach"] = {{"interaction_range", {1}}};
  const CalibrationReport control = run_calibration(beyond_range_1(only_1), alone);
  ASSERT_GT(control.history.size(), 25u + 4u);
  RangedEvaluator e;
  e.noise = 0.1;
  const CalibrationReport r = run_calibration(beyond_range_1(noisy_bayes), e);
  ASSERT_EQ(r.reach ? r.reach->tried.size() : 0u, 2u);
  const ReachAttempt& first = r.reach->tried[0];
  EXPECT_EQ(reach_probe_runs(100), 25);
  EXPECT_GE(first.history.size(), 25u);
  EXPECT_LE(first.history.size(), 25u + 4u);
  EXPECT_FALSE(first.ratio->target_inside());
  EXPECT_TRUE(r.reach->tried[1].ratio->target_inside());
  EXPECT_LE(first.history.size() + r.history.size(), 100u);
  EXPECT_EQ(r.verdict, Verdict::feasible) << r.verdict_reason;
  EXPECT_NE(r.verdict_reason.find(". Reach: interaction range 1.5: "), std::string::npos)
      << r.verdict_reason;
}

// A search that ends before a quarter of its budget (noise-free runs: its emulators soon hold
// little variance, so it converges and checks) at a range whose runs did not reach the target ratio
// still moves on: the probe's count is what lets a long search leave early, not a reason to stay.
// Measured on the engine: a basalt (UCS/BTS 18) ended at range 1 after 14 runs of 100 and its
// reason said range 1.5 was not tried for want of budget, with 82 evaluations left.
TEST(Reach, ASearchThatEndsEarlyAtARangeThatMissesTheRatioMovesOn) {
  RangedEvaluator e;
  const CalibrationReport r =
      run_calibration(beyond_range_1({{"strategy", "bayes"}, {"max_evaluations", 100}}), e);
  ASSERT_EQ(r.reach ? r.reach->tried.size() : 0u, 2u) << r.verdict_reason;
  const ReachAttempt& first = r.reach->tried[0];
  EXPECT_LT(first.history.size(), std::size_t(reach_probe_runs(100)));  // ended early
  EXPECT_FALSE(first.ratio->target_inside());
  EXPECT_TRUE(r.reach->tried[1].ratio->target_inside());
  EXPECT_EQ(r.verdict, Verdict::feasible) << r.verdict_reason;
  EXPECT_EQ(r.verdict_reason.find("not tried"), std::string::npos) << r.verdict_reason;
}

// The decision to leave is taken once, on the runs the search had then. The runs in flight, read
// after, may bring the ratio back (noise); asked again, the range would end with neither a move
// nor a posterior, a false "failed".
TEST(Reach, TheBayesSearchDecidesToLeaveARangeOnce) {
  RangedEvaluator e;
  e.noise = 0.1;
  const CalibrationCampaign c = beyond_range_1({{"strategy", "bayes"}, {"max_evaluations", 100}});
  int asked = 0;
  const LeaveRange leave = [&](const std::optional<orch::RatioRange>&, int) {
    return ++asked == 1;
  };
  CalibrationReport r;
  EXPECT_TRUE(bayes_calibration(c, e, RunOptions{}, r, leave));
  EXPECT_EQ(asked, 1);
  EXPECT_FALSE(r.posterior);
  EXPECT_GE(r.history.size(), std::size_t(reach_probe_runs(100)));
  EXPECT_LE(r.history.size(), std::size_t(reach_probe_runs(100)) + 4u);
}

std::string refusal(const json& reach, const json& more = json::object()) {
  json overrides = {{"reach", reach}};
  overrides.merge_patch(more);
  return testing::refusal(overrides);
}

TEST(Reach, BadFieldsAreRefusedNamingThem) {
  EXPECT_EQ(refusal(1.5), "reach: must be an object");
  EXPECT_EQ(refusal(json::object()), "reach.interaction_range: is required");
  EXPECT_EQ(refusal({{"interaction_range", json::array()}}),
            "reach.interaction_range: must be an array of 1 to 4 range factors");
  EXPECT_EQ(refusal({{"interaction_range", 1.5}}),
            "reach.interaction_range: must be an array of 1 to 4 range factors");
  EXPECT_EQ(refusal({{"interaction_range", {1, "far"}}}),
            "reach.interaction_range[1]: must be a number");
  EXPECT_EQ(refusal({{"interaction_range", {1, 1.5, 1}}}),
            "reach.interaction_range[2]: is repeated");
  EXPECT_EQ(refusal({{"interaction_range", {1, 2.5}}}),
            "reach.interaction_range[1]: the job at this range: "
            "job.effects.interaction_range.factor: must be in [1.0, 2.0]");
  EXPECT_EQ(refusal({{"interaction_range", {1, 1.5}}, {"coordination", 13}}),
            "reach.coordination: unknown field");
  EXPECT_EQ(refusal({{"interaction_range", {1, 1.5}}},
                    {{"job", {{"effects", {{"interaction_range", {{"factor", 1.2}}}}}}}}),
            "reach.interaction_range: not with job.effects.interaction_range (give the ranges "
            "in one place)");
  EXPECT_EQ(refusal({{"interaction_range", {1, 1.5}}},
                    {{"fidelity", {{"fine", {{"sample", {{"radius", 0.5}}}}}}}}),
            "reach.interaction_range: not with \"fidelity\" (the ranges are tried on one "
            "specimen)");
}

}  // namespace
}  // namespace rockcal::calibration
