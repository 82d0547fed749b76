// Calibration with ensembles: "realisations" is validated like every field, every evaluation runs
// that many seeds, its loads are the ensemble means (failed realisations left out and counted), and
// the report carries each evaluation's mean, standard error and n; "auto" sizes the ensemble from
// a pilot's scatter and the report says what size the scatter called for.
#include <gtest/gtest.h>

#include <cmath>

#include "orchestrator/calibration/driver.hpp"
#include "orchestrator/calibration/ensemble_size.hpp"
#include "synthetic.hpp"

namespace rockcal::calibration {
namespace {

using nlohmann::json;

json random_packing() {
  return {{"job", {{"sample", {{"packing", "random"}}}}}};
}

json with(json overrides) {
  json j = random_packing();
  j.merge_patch(overrides);
  return j;
}

std::pair<std::string, std::string> refusal(const json& overrides) {
  try {
    testing::campaign({1000, 100}, overrides);
  } catch (const orch::RequestError& e) {
    return {e.field, e.what()};
  }
  return {"(accepted)", ""};
}

TEST(CalibrationRealisations, AreValidatedNamingTheField) {
  EXPECT_EQ(testing::campaign({1000, 100}).realisations, 1);
  EXPECT_EQ(testing::campaign({1000, 100}, with({{"realisations", 5}})).realisations, 5);
  for (const json& bad : {json(0), json(101), json(1.5), json("2"), json::array({2})}) {
    EXPECT_EQ(
        refusal(with({{"realisations", bad}})),
        std::make_pair(std::string("realisations"),
                       std::string("realisations: must be an integer in [1, 100], or \"auto\"")))
        << bad.dump();
  }
  EXPECT_EQ(
      refusal({{"realisations", 2}, {"job", {{"sample", {{"lattice", "aligned"}}}}}}),
      std::make_pair(std::string("realisations"),
                     std::string("realisations: the template's specimen is the same under "
                                 "every seed (an aligned FCC lattice without seeded "
                                 "effects): more than one realisation would repeat one run")));
  EXPECT_EQ(refusal({{"realisations", 2}}).first, "(accepted)") << "FCC is seeded by default";
  EXPECT_EQ(refusal(with({{"realisations", 3}, {"seeds", {4, 5}}})),
            std::make_pair(std::string("realisations"),
                           std::string("realisations: give \"realisations\" (every evaluation an "
                                       "ensemble) or \"seeds\" (the best point re-run on other "
                                       "packings), not both")));
  EXPECT_EQ(refusal(with({{"realisations", 1}, {"seeds", {4, 5}}})).first, "(accepted)");
  EXPECT_EQ(refusal(with({{"realisations", "auto"}, {"seeds", {4, 5}}})).first, "realisations");
  EXPECT_EQ(refusal(with({{"max_realisations", 4}})),
            std::make_pair(std::string("max_realisations"),
                           std::string("max_realisations: only with \"realisations\": \"auto\"")));
  EXPECT_EQ(refusal(with({{"realisations", "auto"}, {"max_realisations", 1}})),
            std::make_pair(std::string("max_realisations"),
                           std::string("max_realisations: must be in [2, 100]")));
  EXPECT_EQ(
      refusal({{"realisations", "auto"}, {"job", {{"sample", {{"lattice", "aligned"}}}}}}).first,
      "realisations")
      << "an ensemble of one repeated specimen measures no scatter";
  const CalibrationCampaign a =
      testing::campaign({1000, 100}, with({{"realisations", "auto"}, {"max_realisations", 6}}));
  EXPECT_TRUE(a.auto_realisations);
  EXPECT_EQ(a.max_realisations, 6);
}

TEST(CalibrationEnsembleSize, IsTheLeastThatBringsTheStandardErrorToHalfTheTolerance) {
  EXPECT_EQ(realisations_for(0.01, 0.02), 1);  // se = cv = tolerance / 2 with one run
  EXPECT_EQ(realisations_for(0.0101, 0.02), 2);
  EXPECT_EQ(realisations_for(0.05, 0.02), 25);  // 0.05 / sqrt(25) = 0.01
  EXPECT_EQ(realisations_for(0.396, 0.02), 1569)
      << "what the scatter calls for, even beyond what a campaign may run (the report says it)";
}

// The pilot's scatter, recomputed from the pilot's own outcome.
std::pair<double, double> pilot_cvs(const testing::ModelEvaluator& model,
                                    const CalibrationCampaign& c) {
  const EvaluationRequest& pilot = model.log.front();
  std::vector<double> uct, btt;
  for (std::uint64_t seed = c.sample_seed; seed < c.sample_seed + 3; ++seed) {
    const EvaluationOutcome one = model.evaluate({pilot.point, seed, 1});
    uct.push_back(one.loads->uct_n);
    btt.push_back(one.loads->btt_n);
  }
  const orch::SampleStats u = orch::sample_stats(uct), b = orch::sample_stats(btt);
  return {*u.sd / *u.mean, *b.sd / *b.mean};
}

TEST(CalibrationEnsembleSize, AutoRunsAPilotAndEveryEvaluationAtTheSizeItCallsFor) {
  const BondPoint truth{40, 90};
  CalibrationCampaign c = testing::campaign(testing::power_law(truth),
                                            with({{"realisations", "auto"}, {"tolerance", 0.05}}));
  testing::ModelEvaluator evaluator(testing::power_law);
  evaluator.noise = 0.05;  // uniform: cv about 2.9%
  const CalibrationReport r = run_calibration(c, evaluator);
  ASSERT_GE(evaluator.log.size(), 2u);
  EXPECT_EQ(evaluator.log.front().realisations, kPilotRealisations);
  const auto [cv_uct, cv_btt] = pilot_cvs(evaluator, c);
  const int n = r.ensemble.realisations;
  EXPECT_EQ(n, std::max(realisations_for(cv_uct, 0.05), realisations_for(cv_btt, 0.05)));
  // The least size that does it: one fewer would leave a larger standard error.
  const double cv = std::max(cv_uct, cv_btt);
  EXPECT_LE(cv / std::sqrt(double(n)), 0.025);
  EXPECT_GT(cv / std::sqrt(double(n - 1)), 0.025);
  EXPECT_GT(n, 1);
  for (std::size_t i = 1; i < evaluator.log.size(); ++i) {
    EXPECT_EQ(evaluator.log[i].realisations, n) << "request " << i;
  }
  EXPECT_FALSE(r.ensemble.capped);
  EXPECT_EQ(r.verdict, Verdict::feasible) << r.verdict_reason;
  const json j = to_json(r, c);
  EXPECT_EQ(j["realisations"], n);
  EXPECT_EQ(j["ensemble"]["chosen"], "auto");
  EXPECT_EQ(j["ensemble"]["pilot"]["needed"], n);
  EXPECT_DOUBLE_EQ(j["ensemble"]["pilot"]["cv_uct"].get<double>(), cv_uct);
  EXPECT_EQ(j["ensemble"]["at_best"]["runs"], n);
  EXPECT_NE(j["ensemble"]["why"].get<std::string>().find("chosen from a pilot of 3"),
            std::string::npos)
      << j["ensemble"]["why"];
}

// Which packings a search draws decides whether its best point lands within the tolerance or only
// within it plus the standard error; over a few packing seeds some must land in the second case,
// and each that does must say so.
TEST(CalibrationEnsembleSize, ACappedEnsembleSaysWhatTheScatterCalledFor) {
  int widened = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    CalibrationCampaign c = testing::campaign(
        testing::power_law({40, 90}), with({{"realisations", "auto"}, {"max_realisations", 4}}));
    c.consistency_evaluations = 0;
    c.sample_seed = seed;
    testing::ModelEvaluator evaluator(testing::power_law);
    evaluator.noise = 0.4;  // cv about 23%: hundreds of runs for 1%
    const CalibrationReport r = run_calibration(c, evaluator);
    EXPECT_EQ(r.ensemble.realisations, 4);
    EXPECT_TRUE(r.ensemble.capped);
    ASSERT_TRUE(r.ensemble.pilot.needed);
    EXPECT_GT(*r.ensemble.pilot.needed, 4);
    EXPECT_NE(r.ensemble.why.find("beyond max_realisations"), std::string::npos) << r.ensemble.why;
    EXPECT_NE(r.ensemble.why.find("more than were run"), std::string::npos) << r.ensemble.why;
    // The tolerance test counted the wide standard error: the verdict must not claim 2%.
    if (r.verdict != Verdict::feasible) continue;
    const double e_btt = r.best->loads->btt_n / c.targets.model_loads_n.btt_n - 1;
    const double e_uct = r.best->loads->uct_n / c.targets.model_loads_n.uct_n - 1;
    if (std::max(std::abs(e_uct), std::abs(e_btt)) <= c.tolerance) continue;
    ++widened;
    EXPECT_NE(r.verdict_reason.find("plus each ensemble mean's standard error"), std::string::npos)
        << r.verdict_reason;
    EXPECT_NE(r.verdict_reason.find("not within the tolerance"), std::string::npos);
  }
  EXPECT_GE(widened, 1) << "no seed's best point was met only within its standard error";
}

TEST(CalibrationEnsembleSize, OnePackingPerEvaluationIsSaidToMeasureNoScatter) {
  const CalibrationCampaign c = testing::campaign(testing::power_law({40, 90}));
  testing::ModelEvaluator evaluator(testing::power_law);
  const CalibrationReport r = run_calibration(c, evaluator);
  EXPECT_FALSE(r.ensemble.automatic);
  EXPECT_EQ(r.ensemble.realisations, 1);
  EXPECT_EQ(evaluator.log.front().realisations, 1) << "no pilot when the size is fixed";
  EXPECT_NE(r.ensemble.why.find("no scatter was measured"), std::string::npos) << r.ensemble.why;
}

TEST(CalibrationRealisations, EveryEvaluationIsAnEnsembleAndItsMeanIsWhatIsMatched) {
  const BondPoint truth{40, 90};
  const CalibrationCampaign c =
      testing::campaign(testing::power_law(truth), with({{"realisations", 4}}));
  testing::ModelEvaluator evaluator(testing::power_law);
  evaluator.noise = 0.01;
  evaluator.failure_rate = 0.1;  // by point and seed: some realisations fail, some evaluations too
  const CalibrationReport r = run_calibration(c, evaluator);
  ASSERT_FALSE(r.history.empty());
  int partial = 0;
  for (std::size_t i = 0; i < r.history.size(); ++i) {
    const EvaluationRecord& e = r.history[i];
    ASSERT_EQ(evaluator.log[i].realisations, 4);
    ASSERT_TRUE(e.uct && e.btt);
    ASSERT_EQ(e.uct->realisations.size(), 4u);
    // The mean over the realisations that succeeded, from the model itself.
    double sum = 0;
    int n = 0;
    for (std::uint64_t seed = c.sample_seed; seed < c.sample_seed + 4; ++seed) {
      const EvaluationOutcome one = evaluator.evaluate({e.point, seed, 1});
      if (!one.loads) continue;
      sum += one.loads->uct_n;
      ++n;
    }
    EXPECT_EQ(e.uct->peak_load.n, n);
    EXPECT_EQ(e.uct->failed, 4 - n);
    partial += n > 0 && n < 4;
    if (n == 0) {
      EXPECT_FALSE(e.loads);
      EXPECT_EQ(e.error, "uct: synthetic failure");
      continue;
    }
    ASSERT_TRUE(e.loads);
    EXPECT_DOUBLE_EQ(e.loads->uct_n, sum / n);
    EXPECT_EQ(e.loads->uct_n, *e.uct->peak_load.mean);
    EXPECT_EQ(e.uct->peak_load.se.has_value(), n >= 2);
  }
  EXPECT_GT(partial, 0) << "the test must see realisations left out of an evaluation";
  EXPECT_EQ(r.verdict, Verdict::feasible) << r.verdict_reason;

  const json j = to_json(r, c);
  EXPECT_EQ(j["realisations"], 4);
  const EvaluationRecord& best = *r.best;
  EXPECT_EQ(j["best"]["uct"]["peak_load"], best.loads->uct_n);
  EXPECT_EQ(j["best"]["uct"]["n"], best.uct->peak_load.n);
  EXPECT_EQ(j["best"]["uct"]["se"],
            best.uct->peak_load.se ? json(*best.uct->peak_load.se) : json());
  EXPECT_EQ(j["best"]["ensemble"]["btt"]["realisations"].size(), 4u);
  const json& first = j["history"][0]["ensemble"];
  EXPECT_EQ(first["uct"]["peak_load"]["n"], r.history[0].uct->peak_load.n);
  EXPECT_EQ(first["btt"]["peak_load"]["mean"],
            r.history[0].loads ? json(r.history[0].loads->btt_n) : json());
}

TEST(CalibrationRealisations, OneRealisationIsTheOldEvaluation) {
  const CalibrationCampaign c = testing::campaign(testing::power_law({40, 90}));
  testing::ModelEvaluator evaluator(testing::power_law);
  evaluator.noise = 0.01;
  const CalibrationReport r = run_calibration(c, evaluator);
  for (const EvaluationRecord& e : r.history) {
    ASSERT_TRUE(e.loads);
    const PeakLoads model = testing::power_law(e.point);
    EXPECT_EQ(e.loads->uct_n,
              model.uct_n * (1.0 + 0.01 * testing::hash_unit(e.point, c.sample_seed, 1)));
    EXPECT_EQ(e.uct->peak_load.n, 1);
    EXPECT_FALSE(e.uct->peak_load.se);
  }
  const json j = to_json(r, c);
  EXPECT_EQ(j["realisations"], 1);
  EXPECT_EQ(j["best"]["uct"]["n"], 1);
  EXPECT_EQ(j["best"]["uct"]["se"], nullptr) << "one run has no standard error";
}

}  // namespace
}  // namespace rockcal::calibration
