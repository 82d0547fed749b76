// Focus: E and nu as calibration targets (orchestrator/calibration/stiffness.hpp) on a formula
// engine whose elastic test answers like a random packing, not like eq. 3: the stage finds the
// K_s/K_r that gives the target nu and the K_r that gives the target E, the strength search runs
// at them, the report states both against the targets (in lab units for lab targets), a nu out of
// the packing's reach is said with the reach, and bad fields are refused naming them.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "orchestrator/calibration/driver.hpp"
#include "orchestrator/calibration/report.hpp"
#include "orchestrator/calibration/stiffness.hpp"
#include "synthetic.hpp"

namespace rockcal::calibration {
namespace {

using nlohmann::json;

// A packing stiffer in shear than eq. 3's lattice and softer overall: E = 0.3 K_r (1 + 0.8 q) / R
// and nu = 0.5 / (1 + 0.6 q), q = K_s/K_r. nu spans [0.125, 0.478] over the stage's K_s/K_r.
testing::ElasticConstants packing(const ProbeRequest& p, std::uint64_t /*seed*/) {
  const json& m = p.patch.at("material");
  const double q = ks_over_kr(m.at("nu").get<double>());
  return {0.3 * m.at("kr").get<double>() * (1 + 0.8 * q), 0.5 / (1 + 0.6 * q)};
}

json with_elastic(const json& elastic, int budget = 30) {
  return {{"strategy", "bayes"},
          {"max_evaluations", budget},
          {"bounds", {{"fr0", {10, 1000}}, {"fs0", {10, 1000}}}},
          {"targets", elastic}};
}

TEST(StiffnessStage, ACalibrationMeetsEAndNuAndSearchesTheStrengthsAtThem) {
  const CalibrationCampaign c =
      testing::campaign(testing::power_law({60, 120}),
                        with_elastic({{"youngs_modulus", 5000}, {"poisson_ratio", 0.25}}));
  testing::ModelEvaluator e(testing::power_law);
  e.elastic_model = packing;
  const CalibrationReport r = run_calibration(c, e);
  ASSERT_TRUE(r.stiffness);
  const StiffnessResult& s = *r.stiffness;
  ASSERT_TRUE(s.youngs_modulus_pa && s.poisson_ratio);
  EXPECT_NEAR(*s.youngs_modulus_pa / 5000, 1.0, 0.05);
  EXPECT_NEAR(*s.poisson_ratio, 0.25, 0.03);
  // Eq. 3 at nu 0.25 would give this packing nu 0.29: the search moved K_s/K_r.
  EXPECT_NE(s.setting.nu, 0.25);
  EXPECT_DOUBLE_EQ(s.ks_over_kr, ks_over_kr(s.setting.nu));
  EXPECT_EQ(s.runs.back().phase, "confirm");
  EXPECT_LE(int(s.runs.size()), kStiffnessNuRuns + 1);
  // Every strength run after the stage ran at the stage's stiffnesses.
  EXPECT_EQ(e.template_patch, stiffness_patch(c.job_template, s.setting));
  EXPECT_DOUBLE_EQ(e.template_patch["material"]["kr"].get<double>(), s.kr_n_m);
  EXPECT_GE(r.history.size(), 8u);  // the strength search's start batch at least
  EXPECT_EQ(r.verdict, Verdict::feasible);
  EXPECT_NE(r.verdict_reason.find(". Stiffness: nu 0.2"), std::string::npos) << r.verdict_reason;

  const json j = to_json(r, c)["stiffness"];
  EXPECT_EQ(j["measure"], "elastic");
  EXPECT_DOUBLE_EQ(j["kr"].get<double>(), s.kr_n_m);
  EXPECT_DOUBLE_EQ(j["youngs_modulus_pa"]["target"].get<double>(), 5000);
  EXPECT_EQ(j["youngs_modulus_pa"]["met"], true);
  EXPECT_EQ(j["poisson_ratio"]["met"], true);
  EXPECT_EQ(j["met"], true);
  EXPECT_EQ(j["runs"].size(), s.runs.size());
  EXPECT_EQ(j["why"], s.why);
  // The rock's E and nu are the stage's elastic test's, beside the targets.
  const json rock = to_json(r, c)["rock_properties"];
  EXPECT_EQ(rock["youngs_modulus_pa"]["measure"], "elastic");
  EXPECT_EQ(rock["youngs_modulus_pa"]["runs"], c.seed_matters ? kStiffnessPackings : 1);
  EXPECT_DOUBLE_EQ(rock["youngs_modulus_pa"]["value"].get<double>(), *s.youngs_modulus_pa);
  EXPECT_EQ(rock["youngs_modulus_pa"]["lab"], 5000);
  EXPECT_DOUBLE_EQ(rock["poisson_ratio"]["value"].get<double>(), *s.poisson_ratio);
  EXPECT_EQ(rock["poisson_ratio"]["lab"], 0.25);
}

TEST(StiffnessStage, ANuOutOfThePackingsReachIsSaidWithTheReach) {
  const CalibrationCampaign c =
      testing::campaign(testing::power_law({60, 120}), with_elastic({{"poisson_ratio", 0.05}}));
  testing::ModelEvaluator e(testing::power_law);
  e.elastic_model = packing;
  const CalibrationReport r = run_calibration(c, e);
  ASSERT_TRUE(r.stiffness && r.stiffness->poisson_ratio && r.stiffness->nu_reached_lo);
  EXPECT_FALSE(stiffness_met(*r.stiffness));
  // The search ends at the stiffest shear it may take, where this packing's nu is 0.125.
  EXPECT_NEAR(*r.stiffness->nu_reached_lo, 0.125, 0.005);
  EXPECT_NEAR(r.stiffness->setting.nu, kStiffnessNuLo, 1e-6);
  EXPECT_NE(r.stiffness->why.find("the packing's reach"), std::string::npos) << r.stiffness->why;
  EXPECT_EQ(r.verdict, Verdict::compromise);  // the loads are met, nu is not
}

// Bonds beyond touching neighbours as stiff as the touching ones hold nu near 0.13 whatever K_s/K_r
// (the engine's FCC lattice at range 1.5, docs/reach.md); softening them by the interaction
// range's stiffness_exponent n raises it, by 0.025 per unit of n here.
testing::ElasticConstants lattice_at_range(const ProbeRequest& p, std::uint64_t /*seed*/) {
  const json& m = p.patch.at("material");
  const double q = ks_over_kr(m.at("nu").get<double>());
  const json::json_pointer exponent("/effects/interaction_range/stiffness_exponent");
  const double n = p.patch.contains(exponent) ? p.patch.at(exponent).get<double>() : 0.0;
  return {0.3 * m.at("kr").get<double>() * (1 + 0.8 * q) / (1 + 0.1 * n),
          0.12 + 0.01 / (1 + q) + 0.025 * n};
}

TEST(StiffnessStage, ANuBeyondTheLatticesReachAtARangeSoftensTheLongerBonds) {
  json request = with_elastic({{"youngs_modulus", 5000}, {"poisson_ratio", 0.25}});
  request["reach"] = {{"interaction_range", {1.5}}};
  const CalibrationCampaign c = testing::campaign(testing::power_law({60, 120}), request);
  testing::ModelEvaluator e(testing::power_law);
  e.elastic_model = lattice_at_range;
  const CalibrationReport r = run_calibration(c, e);
  ASSERT_TRUE(r.stiffness && r.stiffness->poisson_ratio && r.stiffness->nu_reached_hi);
  const StiffnessResult& s = *r.stiffness;
  EXPECT_TRUE(stiffness_met(s)) << s.why;
  // K_s/K_r alone reached 0.130 at most; the stage aims at the target less half the tolerance,
  // the smallest softening that meets it: n = (0.235 - 0.1293) / 0.025 = 4.2.
  EXPECT_LT(*s.nu_reached_hi, 0.131);
  EXPECT_NEAR(s.setting.long_bond_exponent, 4.2, 0.3);
  EXPECT_NEAR(*s.poisson_ratio, 0.235, 0.0075);
  EXPECT_NEAR(*s.youngs_modulus_pa / 5000, 1.0, 0.05);
  int soft_runs = 0;
  for (const StiffnessRun& x : s.runs) soft_runs += x.phase == "long_bonds";
  EXPECT_GE(soft_runs, 2);
  EXPECT_LE(soft_runs, kLongBondRuns);
  // The strength search ran at the range with those bonds softened.
  EXPECT_EQ(e.template_patch["effects"]["interaction_range"]["factor"], 1.5);
  EXPECT_EQ(e.template_patch["effects"]["interaction_range"]["stiffness_exponent"],
            s.setting.long_bond_exponent);
  EXPECT_NE(s.why.find("meets the target 0.250 at K_s/K_r 0.0769 with the bonds beyond touching "
                       "softened by ((R_i + R_j) / L)^"),
            std::string::npos)
      << s.why;
  EXPECT_NE(s.why.find("as stiff as the touching ones, they left nu at most 0.129)"),
            std::string::npos)
      << s.why;
  EXPECT_EQ(to_json(r, c)["stiffness"]["long_bond_exponent"], s.setting.long_bond_exponent);
  // At another range a setting without softening states n = 0, so the exponent set here does not
  // stay on in the evaluator's template.
  json at_range = c.job_template;
  at_range["effects"] = {{"interaction_range", {{"factor", 1.8}}}};
  json next = e.template_patch;
  next.merge_patch(stiffness_patch(at_range, StiffnessSetting{}));
  EXPECT_EQ(next["effects"]["interaction_range"]["stiffness_exponent"], 0.0);

  // With touching bonds only there is nothing to soften: the miss is said with the reach.
  testing::ModelEvaluator touching(testing::power_law);
  touching.elastic_model = lattice_at_range;
  const CalibrationCampaign plain =
      testing::campaign(testing::power_law({60, 120}),
                        with_elastic({{"youngs_modulus", 5000}, {"poisson_ratio", 0.25}}));
  const std::optional<StiffnessResult> p = calibrate_stiffness(plain, touching);
  ASSERT_TRUE(p);
  EXPECT_FALSE(stiffness_met(*p));
  EXPECT_EQ(p->setting.long_bond_exponent, 0.0);
  for (const StiffnessRun& x : p->runs) EXPECT_NE(x.phase, "long_bonds");
  EXPECT_FALSE(touching.template_patch.contains("effects"));
  EXPECT_NE(p->why.find("the packing's reach."), std::string::npos) << p->why;
}

// A random packing is another specimen under every seed: each elastic run measures
// kStiffnessPackings of them and the stage matches their mean (here the packings' nu alternates
// 0.05 either side of the formula's).
TEST(StiffnessStage, ARandomPackingsNuIsTheMeanOverPackings) {
  json over = with_elastic({{"youngs_modulus", 5000}, {"poisson_ratio", 0.25}});
  over["job"] = {{"sample", {{"packing", "random"}}}};
  const CalibrationCampaign c = testing::campaign(testing::power_law({60, 120}), over);
  ASSERT_TRUE(c.seed_matters);
  testing::ModelEvaluator e(testing::power_law);
  e.elastic_model = [](const ProbeRequest& p, std::uint64_t seed) {
    testing::ElasticConstants k = packing(p, seed);
    k.poisson_ratio += seed % 2 ? 0.05 : -0.05;
    return k;
  };
  const std::optional<StiffnessResult> s = calibrate_stiffness(c, e);
  ASSERT_TRUE(s && s->poisson_ratio && s->poisson_ratio_sd);
  for (const StiffnessRun& run : s->runs) EXPECT_EQ(run.packings, kStiffnessPackings);
  EXPECT_EQ(s->packings, kStiffnessPackings);
  EXPECT_NEAR(*s->poisson_ratio, 0.25, kStiffnessNuTolerance);
  EXPECT_NEAR(*s->poisson_ratio_sd, 0.05 * std::sqrt(4.0 / 3.0), 1e-9);
  EXPECT_NE(s->why.find("E and nu are means of 4 packings (nu sd 0.058 between them)."),
            std::string::npos)
      << s->why;
}

// E alone: the template's K_s/K_r stays, one run measures E there, K_r is scaled once, one run
// confirms.
TEST(StiffnessStage, AnEAloneScalesKrOnceAtTheTemplatesRatio) {
  const CalibrationCampaign c =
      testing::campaign(testing::power_law({60, 120}), with_elastic({{"youngs_modulus", 5000}}));
  testing::ModelEvaluator e(testing::power_law);
  e.elastic_model = packing;
  const std::optional<StiffnessResult> s = calibrate_stiffness(c, e);
  ASSERT_TRUE(s && s->youngs_modulus_pa);
  ASSERT_EQ(s->runs.size(), 2u);
  EXPECT_EQ(s->runs[0].phase, "start");
  EXPECT_EQ(s->runs[1].phase, "confirm");
  EXPECT_DOUBLE_EQ(s->setting.nu, 0.2);  // the template's
  // E = 0.3 K_r (1 + 0.8 / 3) at eq. 3's K_s/K_r 1/3 for nu 0.2.
  EXPECT_NEAR(s->kr_n_m, 5000 / (0.3 * (1 + 0.8 / 3)), 1e-6);
  EXPECT_NEAR(*s->youngs_modulus_pa, 5000, 1e-6);
  EXPECT_EQ(to_json(*s, c)["poisson_ratio"], nullptr);
}

// The seed lab case with the lab's E and nu as targets (the example request): the E target is the
// lab's times eq. 4's stress scale, and the report gives the measured E back in lab units.
TEST(StiffnessStage, LabTargetsAreMatchedInTheModelsUnitsAndReportedInTheLabs) {
  std::ifstream in(std::string(ROCKCAL_SOURCE_DIR) + "/examples/calibrate_seed_lab_stiffness.json");
  const CalibrationCampaign c = parse_calibration_campaign(json::parse(in));
  EXPECT_EQ(c.targets.elastic.poisson_ratio, 0.2);
  ASSERT_TRUE(c.targets.scaling);
  EXPECT_DOUBLE_EQ(*model_youngs_modulus_pa(c.targets), 12.33e9 * c.targets.scaling->stress);
  testing::ModelEvaluator e(testing::power_law);
  e.elastic_model = packing;
  const std::optional<StiffnessResult> s = calibrate_stiffness(c, e);
  ASSERT_TRUE(s && s->youngs_modulus_pa);
  const json lab = to_json(*s, c)["lab"]["youngs_modulus_pa"];
  EXPECT_EQ(lab["target"], 12.33e9);
  EXPECT_NEAR(lab["measured"].get<double>() / 12.33e9, 1.0, 0.05);
}

std::string error(const json& targets, const json& more = json::object()) {
  json over = {{"targets", targets}};
  over.merge_patch(more);
  return testing::refusal(over);
}

TEST(StiffnessStage, BadElasticTargetsAreRefusedNamingTheField) {
  EXPECT_EQ(error({{"poisson_ratio", 0.5}}), "targets.poisson_ratio: must be in (-1, 0.5)");
  EXPECT_EQ(error({{"poisson_ratio", "0.2"}}), "targets.poisson_ratio: must be a number");
  EXPECT_EQ(error({{"youngs_modulus", -3e9}}), "targets.youngs_modulus: must be positive");
  EXPECT_EQ(error({{"youngs_modulus", 5000}},
                  {{"fidelity", {{"fine", {{"sample", {{"radius", 0.5}}}}}}}}),
            "targets.youngs_modulus: not with \"fidelity\" (the stiffness stage calibrates one "
            "specimen)");
  EXPECT_EQ(error({{"youngs_modulus", 5000}, {"poisson_ratio", 0.3}}), "accepted");
}

}  // namespace
}  // namespace rockcal::calibration
