// Focus: the held-out log predictive density and the evidence that ranks the candidates
// (evidence.hpp), with exact numbers: which observations count, the variance each term uses (lab
// uncertainty, budget, the surface emulator's variance, the floor), charged residuals, and the
// evidence of an effect as its density minus the base model's over the observations both predict,
// each candidate's from its real runs or its surfaces, the spread its fit leaves, and the ranking
// by it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "orchestrator/diagnosis/analysis/evidence.hpp"
#include "orchestrator/diagnosis/analysis/fit_spread.hpp"
#include "orchestrator/diagnosis/analysis/gap.hpp"
#include "orchestrator/diagnosis/analysis/verdict.hpp"

namespace rockcal::diagnosis {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

Target target(const char* id, Role role, double sigma, double value = 1.0) {
  Target t;
  t.id = id;
  t.role = role;
  t.sigma = sigma;
  t.value = value;
  t.conditions = {TestKind::uct, 10, 20, 5, 0, 0.05};
  return t;
}

// A calibration observation, two held-out ones with v = 0.03^2 + 0.04^2 = 0.05^2 + 0^2 = 0.0025,
// and a held-out one whose run failed.
std::vector<Target> four() {
  std::vector<Target> t = {
      target("cal", Role::calibration, 0.02), target("held-1", Role::held_out, 0.03),
      target("held-2", Role::held_out, 0.05), target("held-3", Role::held_out, 0.05)};
  t[2].conditions.height_m = 30;  // other conditions: no pair of one specimen
  t[3].conditions.height_m = 40;
  return t;
}
const std::vector<double> kBudget = {0.01, 0.04, 0.0, 0.0};

TEST(HeldOutDensity, SumsTheHeldOutTermsWithBudgetAndLabVariance) {
  const HeldOutDensity d = held_out_density({0.5, 0.1, -0.05, kNan}, four(), kBudget);
  ASSERT_EQ(d.terms.size(), 2u);  // the calibration observation and the failed run do not count
  EXPECT_EQ(d.terms[0].target, 1u);
  EXPECT_EQ(d.terms[1].target, 2u);
  EXPECT_DOUBLE_EQ(d.terms[0].variance, 0.0025);
  EXPECT_DOUBLE_EQ(d.terms[1].variance, 0.0025);
  EXPECT_DOUBLE_EQ(d.terms[0].residual, 0.1);
  // -0.5 (0.1^2 / 0.0025 + ln(2 pi 0.0025)) and -0.5 (0.05^2 / 0.0025 + ln(2 pi 0.0025)).
  EXPECT_NEAR(d.terms[0].lpd, 0.07679374034931774, 1e-12);
  EXPECT_NEAR(d.terms[1].lpd, 1.5767937403493182, 1e-12);
  EXPECT_NEAR(d.lpd, 1.653587480698636, 1e-12);
}

TEST(HeldOutDensity, APredictionFromSurfacesAddsTheirErrorAndOneWithoutItIsLeftOut) {
  // held-1: v = 0.0025 + 0.0075 = 0.01; held-2 has no surface (NaN): left out.
  const HeldOutDensity d =
      held_out_density({0.5, 0.1, -0.05, kNan}, four(), kBudget, {0.0, 0.0075, kNan, 0.0});
  ASSERT_EQ(d.terms.size(), 1u);
  EXPECT_DOUBLE_EQ(d.terms[0].variance, 0.01);
  EXPECT_NEAR(d.lpd, 0.8836465597893729, 1e-12);  // -0.5 (1 + ln(2 pi 0.01))
}

TEST(HeldOutDensity, AnExactValueWithoutBudgetHasTheFloorVariance) {
  std::vector<Target> t = four();
  t[1].sigma = 0.0;
  const HeldOutDensity d = held_out_density({0.0, 0.002, kNan, kNan}, t, {0, 0, 0, 0});
  ASSERT_EQ(d.terms.size(), 1u);
  EXPECT_DOUBLE_EQ(d.terms[0].variance, kMinNoiseScale * kMinNoiseScale);
  EXPECT_NEAR(d.lpd, 3.9888167457774646, 1e-12);  // -0.5 (4 + ln(2 pi 1e-6))
}

// Two held-out UCTs of one specimen, 1.0 and 1.5 (+-2%): a model between them is charged nothing.
TEST(HeldOutDensity, ReadsChargedResiduals) {
  const std::vector<Target> t = {target("a", Role::held_out, 0.02, 1.0),
                                 target("b", Role::held_out, 0.02, 1.5)};
  const double sim = std::log(1.2);
  const HeldOutDensity d = held_out_density({sim - std::log(1.0), sim - std::log(1.5)}, t, {0, 0});
  ASSERT_EQ(d.terms.size(), 2u);
  EXPECT_EQ(d.terms[0].residual, 0.0);
  EXPECT_EQ(d.terms[1].residual, 0.0);
  EXPECT_NEAR(d.lpd, 2 * 2.9930844722234733, 1e-12);  // -0.5 ln(2 pi 0.0004), twice
}

// The effect brings held-1 from 0.1 to 0.02 at equal variance: 0.5 (0.1^2 - 0.02^2) / 0.0025 =
// 1.92 nats. Only observations both models predict count: the effect's held-3 has no partner.
TEST(Evidence, IsTheDensityOverTheBaseModelsOnTheObservationsBothPredict) {
  const HeldOutDensity base = held_out_density({0.5, 0.1, -0.05, kNan}, four(), kBudget);
  const HeldOutDensity effect = held_out_density({0.0, 0.02, -0.05, 0.3}, four(), kBudget);
  ASSERT_EQ(effect.terms.size(), 3u);
  ASSERT_TRUE(evidence_over(effect, base));
  EXPECT_NEAR(*evidence_over(effect, base), 1.92, 1e-12);
  EXPECT_NEAR(*evidence_over(base, effect), -1.92, 1e-12);
  EXPECT_FALSE(evidence_over(effect, HeldOutDensity{}));
}

CandidateResult candidate(const char* effect, bool confirmed, std::vector<double> ln_sim) {
  CandidateResult c;
  c.candidate.effect = effect;
  c.fitted = true;
  c.confirmed = confirmed;
  (confirmed ? c.confirmed_ln : c.predicted) = std::move(ln_sim);
  if (*effect) c.identifiability = Identifiability{true, {}, {0}};
  return c;
}

// A 2-D surface through a 4 x 4 grid of a plane, with run scatter `scatter` (0: exact runs).
Surface plane_surface(double scatter) {
  std::vector<std::vector<double>> z;
  std::vector<double> y;
  int k = 0;
  for (double a : {0.0, 1.0 / 3, 2.0 / 3, 1.0})
    for (double b : {0.0, 1.0 / 3, 2.0 / 3, 1.0}) {
      z.push_back({a, b});
      y.push_back(0.3 * a - 0.2 * b + scatter * ((k++ * 7) % 5 - 2) / 2.0);
    }
  return *fit_surface(z, y);
}

double lpd_term(double r, double v) {
  return -0.5 * (r * r / v + std::log(2.0 * std::numbers::pi * v));
}

// Real runs for the base and a confirmed effect; surfaces with the emulator's variance at their
// fitted point for the others. Lab values 1 (ln 0), so ln(sim) is the residual.
TEST(Evidence, EachCandidateFromItsRunsOrItsSurfacesRanksTheEffects) {
  std::vector<CandidateResult> c = {
      candidate("", true, {0.5, 0.1, -0.05, kNan}),
      candidate("from-surfaces", false, {0.0, 0.1, -0.05, 0.0}),
      candidate("without-surfaces", false, {0.0, 0.0, 0.0, 0.0}),
      candidate("confirmed", true, {0.0, 0.02, -0.05, 0.3}),
  };
  const Surface exact = plane_surface(0.0), rough = plane_surface(0.1);
  c[1].surfaces.per_target = {exact, rough, std::nullopt, exact};
  c[1].calibration.z = {0.5, 0.5};
  c[2].surfaces.per_target = {std::nullopt, std::nullopt, std::nullopt, std::nullopt};
  c[2].calibration.z = {0.5, 0.5};
  c[1].g_surface = 0.1;
  c[2].g_surface = 0.9;  // a larger G, but no evidence to rank by
  mark_evidence(c, four(), {0, 0, 0, 0}, kBudget);
  ASSERT_TRUE(c[0].density && c[1].density && c[3].density);
  EXPECT_FALSE(c[0].evidence);
  // held-1 with v = 0.0025 + the rough surface's variance at the fit, held-2 left out (no
  // surface), held-3 with the exact one's: r = 0.
  const double v_rough = variance_at(rough, c[1].calibration.z);
  const double v_exact = variance_at(exact, c[1].calibration.z);
  EXPECT_GT(v_rough, 1e-4) << "scattered runs leave the emulator unsure";
  EXPECT_LT(v_exact, 0.1 * v_rough);
  // The fit's spread (fit_spread.hpp) adds to both; the base's and the confirmed effect's runs
  // have no surfaces here, so none.
  const std::vector<double> spread = fit_spread(c[1].surfaces, c[1].calibration.z, four(), kBudget);
  EXPECT_GT(spread[1], 0.0);
  ASSERT_EQ(c[1].density->terms.size(), 2u);
  EXPECT_DOUBLE_EQ(c[1].density->terms[0].variance, 0.0025 + (spread[1] + v_rough));
  EXPECT_NEAR(
      c[1].density->lpd,
      lpd_term(0.1, 0.0025 + spread[1] + v_rough) +
          lpd_term(0.0, std::max(0.0025 + spread[3] + v_exact, kMinNoiseScale * kMinNoiseScale)),
      1e-12);
  // On held-1, the one both predict: the base's real run has no emulator variance.
  EXPECT_NEAR(*c[1].evidence, lpd_term(0.1, 0.0025 + spread[1] + v_rough) - lpd_term(0.1, 0.0025),
              1e-12);
  EXPECT_FALSE(c[2].density) << "no held-out observation scored: no density, not an lpd of 0";
  EXPECT_FALSE(c[2].evidence);
  EXPECT_NEAR(*c[3].evidence, 1.92, 1e-12);
  EXPECT_EQ(rank_effects(c), (std::vector<int>{3, 1, 2}));
  EXPECT_EQ(c[3].rank, 1);
  EXPECT_EQ(c[2].rank, 3);
  // The variance is the emulator's at the fitted point: beyond the runs it is larger.
  c[1].calibration.z = {2.0, 2.0};
  EXPECT_GT(predictive_variance(c[1], four(), kBudget)[1], 10.0 * v_rough);
}

// A surface through a 4 x 4 grid of the plane a z_0 + b z_1 (exact runs).
Surface linear_surface(double a, double b) {
  std::vector<std::vector<double>> z;
  std::vector<double> y;
  for (double u : {0.0, 1.0 / 3, 2.0 / 3, 1.0})
    for (double v : {0.0, 1.0 / 3, 2.0 / 3, 1.0}) {
      z.push_back({u, v});
      y.push_back(a * u + b * v);
    }
  return *fit_surface(z, y);
}

// Focus: the fit's spread (fit_spread.hpp). A calibration observation that sees only
// z_0 + z_1 (scale 0.05) fixes that direction and leaves z_0 - z_1 to the box's prior (variance
// 1/12): a held-out observation along the loose direction is predicted with the prior's spread,
// (1, -1) Sigma (1, -1)^T = 2 / 12, one along the calibrated direction with what the calibration
// leaves, 2 / (12 + 2 / 0.05^2). A base model that misses the loose observation by 0.5 in ln is
// not charged as if its fit were exact.
TEST(FitSpread, AHeldOutObservationTheCalibrationLeavesLooseCarriesTheBoxsSpread) {
  const std::vector<Target> t = {
      target("cal", Role::calibration, 0.05), target("loose", Role::held_out, 0.05),
      target("along", Role::held_out, 0.05), target("no-surface", Role::held_out, 0.05)};
  SurfaceSet s;
  s.dims = 2;
  s.per_target = {linear_surface(1, 1), linear_surface(1, -1), linear_surface(1, 1), std::nullopt};
  const std::vector<double> budget(4, 0.0);
  const std::vector<double> v = fit_spread(s, {0.5, 0.5}, t, budget);
  ASSERT_EQ(v.size(), 4u);
  EXPECT_NEAR(v[0], 2.0 / 812.0, 1e-6);
  EXPECT_NEAR(v[1], 2.0 / 12.0, 1e-6);
  EXPECT_NEAR(v[2], 2.0 / 812.0, 1e-6);
  EXPECT_EQ(v[3], 0.0) << "no surface, no sensitivity to carry";
  // More calibration noise widens the calibrated direction only.
  const std::vector<double> noisy = fit_spread(s, {0.5, 0.5}, t, {0.1, 0.0, 0.0, 0.0});
  EXPECT_NEAR(noisy[2], 2.0 / (12.0 + 2.0 / 0.0125), 1e-6);
  EXPECT_NEAR(noisy[1], 2.0 / 12.0, 1e-6);

  std::vector<CandidateResult> c = {candidate("", true, {0.0, 0.5, 0.0, 0.0})};
  c[0].surfaces = s;
  c[0].calibration.z = {0.5, 0.5};
  mark_evidence(c, t, {0, 0, 0, 0}, budget);
  ASSERT_TRUE(c[0].density);
  ASSERT_EQ(c[0].density->terms.size(), 3u);
  EXPECT_NEAR(c[0].density->terms[0].variance, 0.0025 + 2.0 / 12.0, 1e-6);
  EXPECT_NEAR(c[0].density->terms[1].variance, 0.0025 + 2.0 / 812.0, 1e-6);
  EXPECT_DOUBLE_EQ(c[0].density->terms[2].variance, 0.0025);
}

// An effect fitted where it does nothing (an interaction range below the FCC's next neighbours
// is the base model) can still gain evidence, from its strengths' re-fit: measured against the
// base model at the same strengths it moves nothing beyond noise, and it is not named.
// An effect whose real runs lie further from the held-out data than the base model's (G <= 0) can
// still gain evidence from the spread its loosely fixed parameter leaves in its predictions (a
// vaguer model outscores a base that misses by several noise units): it is never named, and the
// reason says why; with G > 0 the same evidence names it.
TEST(Evidence, AnEffectNoCloserToTheHeldOutDataThanTheBaseIsNeverTheVerdict) {
  std::vector<CandidateResult> c = {candidate("", true, {0.0, 0.2, 0.0, 0.0}),
                                    candidate("compression_coupling", true, {0.0, 0.3, 0.0, 0.0})};
  c[0].confirmed_rms.held_out = 0.2;
  c[1].confirmed_rms.held_out = 0.3;
  c[1].evidence = 10.66;
  c[1].g_confirmed = -0.5;
  const DecisionRule rule;
  Verdict v = decide(rule, c, {1}, 2.8, 0.061);
  EXPECT_EQ(v.candidate, -1) << v.reason;
  EXPECT_NE(v.reason.find("compression_coupling (evidence 10.66 nats) is not the explanation: its "
                          "runs miss the held-out observations by more than the base model's (G = "
                          "-0.50), so what it gained is the width of its prediction, not a closer "
                          "one"),
            std::string::npos)
      << v.reason;
  // Inert at its fit too (the Zigong sandstone's coupling, G -0.06): given that one reason, once.
  c[1].mark_at_fit = 0.2;
  v = decide(rule, c, {1}, 2.8, 0.061);
  EXPECT_EQ(v.candidate, -1);
  const std::string once =
      "compression_coupling (evidence 10.66 nats) is not the explanation: at "
      "its fitted value it changes no observation";
  const std::size_t at = v.reason.find(once);
  EXPECT_NE(at, std::string::npos) << v.reason;
  EXPECT_EQ(v.reason.find("compression_coupling (evidence", at + 1), std::string::npos) << v.reason;
  c[1].mark_at_fit.reset();
  c[1].g_confirmed = 0.0;  // no closer is not closer
  EXPECT_EQ(decide(rule, c, {1}, 2.8, 0.061).candidate, -1);
  c[1].g_confirmed = 0.1;
  v = decide(rule, c, {1}, 2.8, 0.061);
  EXPECT_EQ(v.candidate, 1) << v.reason;
  EXPECT_EQ(v.reason.find("is not the explanation"), std::string::npos) << v.reason;
}

// Focus: a named effect whose fit lies on the search box says so: with its parameter at the end
// of its range (a rate twin hidden at twice the candidate's strong value, named at it) the effect
// may be stronger than the range reaches, and its figures are the bound's.
TEST(Evidence, ANamedEffectFittedOnTheBoxSaysSo) {
  std::vector<CandidateResult> c = {candidate("", true, {0.0, 0.2, 0.0, 0.0}),
                                    candidate("rate", true, {0.0, 0.1, 0.0, 0.0})};
  c[0].confirmed_rms.held_out = 0.2;
  c[1].confirmed_rms.held_out = 0.1;
  c[1].evidence = 2.36;
  c[1].g_confirmed = 0.5;
  c[1].candidate.param = "speed_factor";
  c[1].candidate.value_at = [](double s) { return std::pow(8.0, s); };
  c[1].calibration.z = {0.4, 0.5, 0.3};
  const DecisionRule rule;
  Verdict v = decide(rule, c, {1}, 2.8, 0.061);
  ASSERT_EQ(v.candidate, 1) << v.reason;
  EXPECT_EQ(v.reason.find("search box"), std::string::npos) << v.reason;
  c[1].calibration.z = {0.4, 0.5, 1.0};
  v = decide(rule, c, {1}, 2.8, 0.061);
  ASSERT_EQ(v.candidate, 1) << v.reason;
  EXPECT_NE(v.reason.find("; its fit lies on the search box (s upper): speed_factor 8.000 is the "
                          "end of the range tried, and the effect may be stronger than that, so "
                          "its figures are the bound's, not an optimum's; the base model's"),
            std::string::npos)
      << v.reason;
  c[1].calibration.z = {0.0, 0.5, 0.3};
  v = decide(rule, c, {1}, 2.8, 0.061);
  EXPECT_NE(v.reason.find("; its fit lies on the search box (fr0 lower), so its figures are the "
                          "bound's, not an optimum's"),
            std::string::npos)
      << v.reason;
}

TEST(Evidence, AnEffectInertAtItsFittedValueIsNeverTheVerdict) {
  std::vector<CandidateResult> c = {candidate("", true, {0.0, 0.2, 0.0, 0.0}),
                                    candidate("interaction_range", true, {0.0, 0.05, 0.0, 0.0}),
                                    candidate("rate", true, {0.0, 0.15, 0.0, 0.0})};
  c[0].confirmed_rms.held_out = 0.2;
  c[1].confirmed_rms.held_out = 0.05;
  c[2].confirmed_rms.held_out = 0.15;
  c[1].evidence = 9.25;
  c[2].evidence = 2.5;
  c[1].mark_at_fit = 0.4;  // its run against the base model's at the same strengths
  c[2].mark_at_fit = 3.0;
  const DecisionRule rule;
  Verdict v = decide(rule, c, {1, 2}, 2.3, 0.177);
  EXPECT_EQ(v.candidate, 2) << v.reason;
  c[2].mark_at_fit = 1.0;  // at most its noise: inert too
  v = decide(rule, c, {1, 2}, 2.3, 0.177);
  EXPECT_EQ(v.candidate, -1);
  EXPECT_NE(v.reason.find("no candidate effect is identifiable from these observations, able to "
                          "fit the calibration observations and active at its fitted value; "
                          "interaction_range (evidence 9.25 nats) is not the explanation: at its "
                          "fitted value it changes no observation beyond its noise against the "
                          "base model at the same strengths (largest change 0.40 of its noise), so "
                          "what it gained is the strengths' re-fit, not the effect"),
            std::string::npos)
      << v.reason;
  // Without the check's run (an older report, a base candidate) nothing is assumed inert.
  c[1].mark_at_fit.reset();
  EXPECT_EQ(decide(rule, c, {1, 2}, 2.3, 0.177).candidate, 1);
  // The same evidence with the base model within the rule's budgets: not named, and said why.
  const Verdict within = decide(rule, c, {1, 2}, 0.997, 0.177);
  EXPECT_EQ(within.candidate, -1);
  EXPECT_NE(within.reason.find("within the 1.00 budgets of the decision rule, no gap to explain; "
                               "the best effect, "),
            std::string::npos)
      << within.reason;
  EXPECT_NE(within.reason.find(", above the threshold, but without a gap there is nothing for it "
                               "to explain"),
            std::string::npos)
      << within.reason;
}

// The rule names the contender with the most evidence when it exceeds the threshold, and only
// where the base model leaves a gap to explain.
TEST(Evidence, TheDecisionRuleNamesTheBestContenderAboveItsThreshold) {
  const DecisionRule rule;  // the default threshold
  const double gap = 2.0;   // held-out rms in noise budgets
  EXPECT_EQ(choose_effect(rule, {{1, rule.min_evidence + 0.5}}, gap), 1);
  EXPECT_EQ(choose_effect(rule, {{1, rule.min_evidence}}, gap), -1) << "exceed, not equal";
  EXPECT_EQ(choose_effect(rule, {{1, rule.min_evidence - 0.5}}, gap), -1);
  EXPECT_EQ(choose_effect(rule, {}, gap), -1);
  DecisionRule strict;
  strict.min_evidence = 5.0;
  EXPECT_EQ(choose_effect(strict, {{1, 4.0}}, gap), -1);
  EXPECT_EQ(choose_effect(strict, {{1, 4.0}, {2, 6.0}}, gap), 2);
  EXPECT_EQ(choose_effect(strict, {{1, 6.0}, {2, 6.0}}, gap), 1) << "ties keep the earlier";
  // The base model within the rule's budgets (the coupling twin's 0.997) or without held-out
  // residuals: nothing to explain, whatever the evidence.
  EXPECT_EQ(choose_effect(rule, {{1, 1.41}}, 0.997), -1);
  EXPECT_EQ(choose_effect(rule, {{1, 1.41}}, rule.gap_budgets), -1) << "exceed, not equal";
  EXPECT_EQ(choose_effect(rule, {{1, 1.41}}, std::nullopt), -1);
  EXPECT_EQ(choose_effect(rule, {{1, 1.41}}, 1.01), 1);
}

}  // namespace
}  // namespace rockcal::diagnosis
