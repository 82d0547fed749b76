// Calibration with ensembles: "realisations" is validated like every field, every evaluation runs
// that many seeds, its loads are the ensemble means (failed realisations left out and counted), and
// the report carries each evaluation's mean, standard error and n.
#include <gtest/gtest.h>

#include <cmath>

#include "orchestrator/calibration/driver.hpp"
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
  } catch (const CampaignError& e) {
    return {e.field, e.what()};
  }
  return {"(accepted)", ""};
}

TEST(CalibrationRealisations, AreValidatedNamingTheField) {
  EXPECT_EQ(testing::campaign({1000, 100}).realisations, 1);
  EXPECT_EQ(testing::campaign({1000, 100}, with({{"realisations", 5}})).realisations, 5);
  for (const json& bad : {json(0), json(101), json(1.5), json("2"), json::array({2})}) {
    EXPECT_EQ(refusal(with({{"realisations", bad}})),
              std::make_pair(std::string("realisations"),
                             std::string("realisations: must be an integer in [1, 100]")))
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
