// The twin test: targets produced by the engine itself at a known
// (F_r0, F_s0); the calibration, running the real rockcal-dem, must recover both loads within 2%
// and both strengths within the resolution its "unique" claims (a factor kRatioStep) in at most 40
// evaluations. Tiny samples, so it takes seconds per point.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "engine_runner.hpp"
#include "orchestrator/calibration/bayes/emulators.hpp"
#include "orchestrator/calibration/consistent_set.hpp"
#include "orchestrator/calibration/driver.hpp"
#include "orchestrator/calibration/runner_evaluator.hpp"
#include "orchestrator/calibration/stiffness.hpp"

namespace rockcal::calibration {
namespace {

using nlohmann::json;

class Twin : public ::testing::Test {
 protected:
  void SetUp() override {
    // Open MPI refuses root without these (CI runs as root); rockcal-dem runs as a singleton.
    setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 0);
    setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 0);
    work_ = std::filesystem::temp_directory_path() / ("rockcal-twin-" + std::to_string(getpid()));
    engine_.engine = ROCKCAL_DEM;
    engine_.work_dir = work_;
  }
  void TearDown() override { std::filesystem::remove_all(work_); }

  static json job_template() {
    return {{"sample", {{"diameter", 10}, {"height", 28}, {"radius", 1}}},
            {"material", {{"kr", 8000}, {"nu", 0.2}, {"density", 1}}},
            {"loading", {{"max_strain", 0.3}}}};
  }

  std::filesystem::path work_;
  testing::EngineRunner engine_;
  RunnerEvaluator evaluator_{engine_, job_template()};
};

TEST_F(Twin, RecoversTheEngineOwnBondStrengths) {
  const BondPoint truth{80, 120};
  const EvaluationRequest at_truth{truth, 1};
  const EvaluationOutcome target = evaluator_.evaluate_batch(std::span(&at_truth, 1)).front();
  ASSERT_TRUE(target.ok()) << target.error;
  const json campaign_json = {{"kind", "calibration"},
                              {"name", "twin"},
                              {"job", job_template()},
                              {"targets",
                               {{"uct", {{"peak_load", target.loads->uct_n}}},
                                {"btt", {{"peak_load", target.loads->btt_n}}}}},
                              {"bounds", {{"fr0", {10, 400}}, {"fs0", {10, 400}}}},
                              {"max_evaluations", 40},
                              {"tolerance", 0.02}};
  const CalibrationCampaign c = parse_calibration_campaign(campaign_json);
  const CalibrationReport r = run_calibration(c, evaluator_);
  const json report = to_json(r, c);
  std::printf("twin: %zu evaluations, verdict %s, strategy %s, best (%g, %g), homogeneity %s\n",
              r.history.size(), to_string(r.verdict), r.strategy_used.c_str(),
              r.best ? r.best->point.fr0_n : 0.0, r.best ? r.best->point.fs0_n : 0.0,
              report["homogeneity"].dump().c_str());
  std::printf("twin: consistent %s, unique %d (%s)\n", report["consistent"]["fr0"].dump().c_str(),
              int(r.consistent.unique), r.consistent.why.c_str());
  std::printf("twin: consistent F_s0 %s\n", report["consistent"]["fs0"].dump().c_str());
  RecordProperty("evaluations", int(r.history.size()));
  ASSERT_TRUE(r.best.has_value());
  EXPECT_EQ(r.verdict, Verdict::feasible) << r.verdict_reason;
  EXPECT_LE(r.history.size() - r.trace.evaluations, 40u) << "the search's budget";
  EXPECT_NEAR(r.best->loads->uct_n / target.loads->uct_n, 1.0, 0.02);
  EXPECT_NEAR(r.best->loads->btt_n / target.loads->btt_n, 1.0, 0.02);
  EXPECT_TRUE(r.consistent.unique) << r.consistent.why;
  // "Unique" pins each strength to within one ratio step of the best point, the truth included.
  // (On this 10 x 28 cylinder loads jump by a few per cent between nearby strengths, so a point
  // 15% from the truth in one strength can meet both loads within 2%, as on a generic x86-64
  // build's round-off.)
  EXPECT_LE(std::abs(std::log(r.best->point.fr0_n / truth.fr0_n)), std::log(kRatioStep));
  EXPECT_LE(std::abs(std::log(r.best->point.fs0_n / truth.fs0_n)), std::log(kRatioStep));
  EXPECT_NE(r.consistent.why.find("each strength is pinned to within a factor 1.2"),
            std::string::npos)
      << r.consistent.why;
}

// Past some F_s0/F_r0 the bonds break mostly in tension: both loads then hardly depend on F_s0 and
// a long valley of strengths meets them. Whatever member the search finds, the report must not
// call it unique, and must say why. (Whether the truth lies in the traced set is not asserted:
// the walk stops at the first step that misses, and on this 10 x 28 cylinder a step's loads jump
// by several per cent, so the traced piece of the valley moves with the engine's round-off; the
// bayes strategy's region is the answer that is checked to hold the truth.)
TEST_F(Twin, TwoLoadsThatDoNotPinTheStrengthsAreReportedNotUnique) {
  const json tmpl = job_template();
  const BondPoint truth{40, 300};
  const EvaluationRequest at_truth{truth, 1};
  const EvaluationOutcome target = evaluator_.evaluate_batch(std::span(&at_truth, 1)).front();
  ASSERT_TRUE(target.ok()) << target.error;
  const json campaign_json = {{"kind", "calibration"},
                              {"name", "twin"},
                              {"job", tmpl},
                              {"targets",
                               {{"uct", {{"peak_load", target.loads->uct_n}}},
                                {"btt", {{"peak_load", target.loads->btt_n}}}}},
                              {"bounds", {{"fr0", {10, 400}}, {"fs0", {10, 2000}}}},
                              {"max_evaluations", 40},
                              {"consistency_evaluations", 24},
                              // The tiny cylinder's loads jump by ~4% between nearby strengths
                              // (a few bonds decide its peak): a tolerance above that noise.
                              {"tolerance", 0.06}};
  const CalibrationCampaign c = parse_calibration_campaign(campaign_json);
  const CalibrationReport r = run_calibration(c, evaluator_);
  const json report = to_json(r, c);
  std::printf(
      "twin tension-only: %zu evaluations, best (%g, %g), consistent F_r0 %s F_s0 %s, unique %d: "
      "%s\n",
      r.history.size(), r.best ? r.best->point.fr0_n : 0.0, r.best ? r.best->point.fs0_n : 0.0,
      report["consistent"]["fr0"].dump().c_str(), report["consistent"]["fs0"].dump().c_str(),
      int(r.consistent.unique), r.consistent.why.c_str());
  std::printf("twin tension-only: trace %s\n", report["consistent"]["trace"].dump().c_str());
  ASSERT_TRUE(r.best.has_value());
  EXPECT_EQ(r.verdict, Verdict::feasible) << r.verdict_reason;
  EXPECT_FALSE(r.consistent.unique);
  EXPECT_NE(r.consistent.why.find("the two loads do not pin both strengths"), std::string::npos)
      << r.consistent.why;
  EXPECT_GT(r.consistent.fs0.hi / r.consistent.fs0.lo, 1.5) << "a valley, not a point";
}

}  // namespace
}  // namespace rockcal::calibration

namespace rockcal::calibration {
namespace {

// The "bayes" strategy on the real engine: the lab is the engine's own mean over four packings at
// a known (F_r0, F_s0), stated to the standard error those four give; the credible region the
// calibration returns from 40 single-packing runs must hold the truth, and the predicted loads at
// its estimate meet the targets.
TEST_F(Twin, TheBayesRegionHoldsTheEngineOwnBondStrengths) {
  const BondPoint truth{80, 120};
  std::vector<EvaluationRequest> lab;
  for (std::uint64_t seed = 101; seed <= 104; ++seed) lab.push_back({truth, seed, 1});
  json seeded = job_template();
  seeded["sample"]["lattice"] = "seeded";
  seeded["sample"]["seed"] = 1;
  RunnerEvaluator evaluator(engine_, seeded);
  const std::vector<EvaluationOutcome> runs = evaluator.evaluate_batch(lab);
  double lu = 0, lb = 0, su = 0, sb = 0;
  for (const EvaluationOutcome& o : runs) {
    ASSERT_TRUE(o.ok()) << o.error;
    lu += std::log(o.loads->uct_n) / 4, lb += std::log(o.loads->btt_n) / 4;
  }
  for (const EvaluationOutcome& o : runs) {
    su += std::pow(std::log(o.loads->uct_n) - lu, 2) / 3;
    sb += std::pow(std::log(o.loads->btt_n) - lb, 2) / 3;
  }
  // The standard error of each lab mean in ln, at least 2%.
  const double se_uct = std::max(0.02, std::sqrt(su / 4)),
               se_btt = std::max(0.02, std::sqrt(sb / 4));
  const json campaign_json = {
      {"kind", "calibration"},
      {"name", "bayes twin"},
      {"job", seeded},
      {"targets", {{"uct", {{"peak_load", std::exp(lu)}}}, {"btt", {{"peak_load", std::exp(lb)}}}}},
      {"bounds", {{"fr0", {10, 400}}, {"fs0", {10, 400}}}},
      {"strategy", "bayes"},
      {"max_evaluations", 40},
      {"tolerance", 0.02},
      {"inference", {{"lab_uncertainty", {{"uct", se_uct}, {"btt", se_btt}}}}}};
  const CalibrationCampaign c = parse_calibration_campaign(campaign_json);
  const CalibrationReport r = run_calibration(c, evaluator);
  ASSERT_TRUE(r.posterior) << r.verdict_reason;
  const PosteriorSummary& p = *r.posterior;
  std::printf("bayes twin: %d runs, lab se %.3f/%.3f, F_r0 [%g, %g], F_s0 [%g, %g], verdict %s\n",
              p.runs, se_uct, se_btt, p.fr0.lo, p.fr0.hi, p.fs0.lo, p.fs0.hi, to_string(r.verdict));
  EXPECT_LE(r.history.size(), 40u);
  EXPECT_TRUE(in_credible_region(p, truth)) << r.verdict_reason;
  EXPECT_EQ(r.verdict, Verdict::feasible) << r.verdict_reason;
}

// The stiffness stage on the real engine: a random packing, which eq. 3 does not describe (its
// packings' mean nu at eq. 3's K_s/K_r for nu 0.24 is 0.19; the stage's smallest K_s/K_r, 0.077,
// gives 0.247 on this specimen), must meet a nu its K_s/K_r reach
// within 0.03 and the target E within 5% as means of kStiffnessPackings packings, and leave the
// evaluator's template at the stiffnesses it reports.
TEST_F(Twin, TheStiffnessStageMeetsAReachableNuAndTheTargetEOnARandomPacking) {
  json random = job_template();
  random["sample"] = {{"diameter", 16},      {"height", 32},        {"radius", 1},
                      {"packing", "random"}, {"radius_ratio", 1.5}, {"seed", 1}};
  RunnerEvaluator evaluator(engine_, random);
  const json campaign_json = {{"kind", "calibration"},
                              {"name", "stiffness twin"},
                              {"job", random},
                              {"targets",
                               {{"uct", {{"peak_load", 2000}}},
                                {"btt", {{"peak_load", 300}}},
                                {"youngs_modulus", 4000},
                                {"poisson_ratio", 0.24}}},
                              {"bounds", {{"fr0", {10, 400}}, {"fs0", {10, 400}}}},
                              {"strategy", "bayes"}};
  const CalibrationCampaign c = parse_calibration_campaign(campaign_json);
  const std::optional<StiffnessResult> s = calibrate_stiffness(c, evaluator);
  ASSERT_TRUE(s && s->youngs_modulus_pa && s->poisson_ratio);
  for (const StiffnessRun& x : s->runs)
    std::printf("  %s K_s/K_r %.3f nu %.3f (sd %.3f) E %.0f\n", x.phase.c_str(),
                ks_over_kr(x.setting.nu), x.poisson_ratio.value_or(-9),
                x.poisson_ratio_sd.value_or(-9), x.youngs_modulus_pa.value_or(0));
  std::printf("stiffness twin: %zu elastic runs, K_r %g, K_s/K_r %g, E %g, nu %g\n%s\n",
              s->runs.size(), s->kr_n_m, s->ks_over_kr, *s->youngs_modulus_pa, *s->poisson_ratio,
              s->why.c_str());
  EXPECT_NEAR(*s->poisson_ratio, 0.24, kStiffnessNuTolerance);
  EXPECT_GE(s->runs.size(), 3u);  // eq. 3's start measures a mean nu 0.19: the search moved it
  EXPECT_NEAR(*s->youngs_modulus_pa / 4000, 1.0, kStiffnessETolerance);
  EXPECT_TRUE(stiffness_met(*s));
  EXPECT_DOUBLE_EQ(evaluator.job_template()["material"]["kr"].get<double>(), s->kr_n_m);
  EXPECT_DOUBLE_EQ(evaluator.job_template()["material"]["nu"].get<double>(), s->setting.nu);
}

}  // namespace
}  // namespace rockcal::calibration
