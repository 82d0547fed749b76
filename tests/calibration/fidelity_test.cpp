// Focus: the multi-fidelity correction. A coarse search, then Newton steps on the
// fine specimen with the coarse model's Jacobian: the fine loads must meet the targets in a few
// fine evaluations, the fine point must be the fine model's solution, and the report must say which
// resolution each evaluation ran at.
#include <gtest/gtest.h>

#include <cmath>

#include "orchestrator/calibration/driver.hpp"
#include "synthetic.hpp"

namespace rockcal::calibration {
namespace {

using nlohmann::json;
using testing::ModelEvaluator;

// The fine specimen (a patch with diameter 12) loads 30% more in the UCT and 15% more in the BTT
// than the coarse one at the same strengths: a common factor and a ratio shift.
constexpr double kFineUct = 1.3, kFineBtt = 1.15;

double fine_probe(const BondPoint& p, const ProbeRequest& probe) {
  const bool fine =
      probe.patch.contains("sample") && probe.patch["sample"].value("diameter", 0.0) == 12;
  const PeakLoads l = testing::power_law(p);
  if (probe.test == TestKind::uct) return l.uct_n * (fine ? kFineUct : 1.0);
  if (probe.test == TestKind::btt) return l.btt_n * (fine ? kFineBtt : 1.0);
  return l.uct_n;
}

TEST(Fidelity, TheFineSpecimenMeetsTheTargetsAfterAFewCorrections) {
  const BondPoint truth{40, 90};
  const PeakLoads targets = testing::power_law(truth);
  const CalibrationCampaign c = testing::campaign(
      targets, {{"fidelity", {{"fine", {{"sample", {{"diameter", 12}}}}}, {"corrections", 3}}}});
  ModelEvaluator evaluator(testing::power_law, fine_probe);
  const CalibrationReport r = run_calibration(c, evaluator);
  ASSERT_TRUE(r.fidelity);
  EXPECT_TRUE(r.fidelity->met) << r.verdict_reason;
  EXPECT_EQ(r.verdict, Verdict::feasible) << r.verdict_reason;
  EXPECT_LE(r.fidelity->steps.size(), 3u);
  ASSERT_TRUE(r.fidelity->factors);
  EXPECT_NEAR(r.fidelity->factors->uct_n, kFineUct, 1e-9) << "measured at the coarse best point";
  EXPECT_NEAR(r.fidelity->factors->btt_n, kFineBtt, 1e-9);
  EXPECT_EQ(r.fidelity->jacobian.rfind("fitted to ", 0), 0u) << r.fidelity->jacobian;
  // The fine model's own solution: 0.3 u + 0.7 v = ln(T_u / 2500 / 1.3), 0.8 u + 0.2 v = ...
  const double a = std::log(targets.uct_n / 2500 / kFineUct);
  const double b = std::log(targets.btt_n / 420 / kFineBtt);
  const double det = 0.3 * 0.2 - 0.7 * 0.8;
  const BondPoint fine_truth{std::exp((a * 0.2 - 0.7 * b) / det),
                             std::exp((0.3 * b - 0.8 * a) / det)};
  const BondPoint& answer = r.fidelity->steps.back().point;
  EXPECT_NEAR(answer.fr0_n / fine_truth.fr0_n, 1.0, 0.10);
  EXPECT_NEAR(answer.fs0_n / fine_truth.fs0_n, 1.0, 0.10);
  const json j = to_json(r, c);
  EXPECT_EQ(j["history"][0]["resolution"], "coarse");
  EXPECT_EQ(j["fidelity"]["steps"].back()["resolution"], "fine");
  EXPECT_EQ(j["fidelity"]["met"], true);
  std::printf(
      "fidelity: %zu coarse evaluations, %zu fine; fine answer (%g, %g), fine truth (%g, %g)\n",
      r.history.size(), r.fidelity->steps.size(), answer.fr0_n, answer.fs0_n, fine_truth.fr0_n,
      fine_truth.fs0_n);
}

// A fine specimen twice as sensitive as the coarse one (ln L_fine = 2 ln L_coarse + const, 1.3x
// and 1.15x the coarse loads at (40, 90)): a Newton step with the coarse Jacobian overshoots by
// exactly its own size, so without the secant update the fine steps swing about the answer for
// ever.
double steeper_fine_probe(const BondPoint& p, const ProbeRequest& probe) {
  const PeakLoads l = testing::power_law(p), at = testing::power_law({40, 90});
  if (probe.test == TestKind::uct) return kFineUct * l.uct_n * l.uct_n / at.uct_n;
  if (probe.test == TestKind::btt) return kFineBtt * l.btt_n * l.btt_n / at.btt_n;
  return l.uct_n;
}

TEST(Fidelity, TheFineStepsLearnTheFineSpecimensSensitivities) {
  const BondPoint truth{40, 90};
  const PeakLoads targets = testing::power_law(truth);
  const CalibrationCampaign c = testing::campaign(
      targets, {{"fidelity", {{"fine", {{"sample", {{"diameter", 12}}}}}, {"corrections", 6}}}});
  ModelEvaluator evaluator(testing::power_law, steeper_fine_probe);
  const CalibrationReport r = run_calibration(c, evaluator);
  ASSERT_TRUE(r.fidelity);
  EXPECT_TRUE(r.fidelity->met) << r.verdict_reason;
  EXPECT_LE(r.fidelity->steps.size(), 5u);
  EXPECT_GE(r.fidelity->secant_updates, 1);
  // The fine model's solution: L_coarse(p) = T / sqrt(factor) for each load.
  const double a = std::log(targets.uct_n / 2500 / std::sqrt(kFineUct));
  const double b = std::log(targets.btt_n / 420 / std::sqrt(kFineBtt));
  const double det = 0.3 * 0.2 - 0.7 * 0.8;
  const BondPoint fine_truth{std::exp((a * 0.2 - 0.7 * b) / det),
                             std::exp((0.3 * b - 0.8 * a) / det)};
  const BondPoint& answer = r.fidelity->steps.back().point;
  EXPECT_NEAR(answer.fr0_n / fine_truth.fr0_n, 1.0, 0.05);
  EXPECT_NEAR(answer.fs0_n / fine_truth.fs0_n, 1.0, 0.05);
  for (const FidelityStep& s : r.fidelity->steps) {
    std::printf("fine step (%.3f, %.3f): UCT %+.2f%%, BTT %+.2f%%\n", s.point.fr0_n, s.point.fs0_n,
                100 * (s.fine->uct_n / targets.uct_n - 1),
                100 * (s.fine->btt_n / targets.btt_n - 1));
  }
  EXPECT_EQ(to_json(r, c)["fidelity"]["secant_updates"], r.fidelity->secant_updates);
}

TEST(Fidelity, WithoutAFineSpecimenTheSearchIsTheAnswer) {
  const CalibrationCampaign c = testing::campaign(testing::power_law({40, 90}));
  ModelEvaluator evaluator(testing::power_law, fine_probe);
  const CalibrationReport r = run_calibration(c, evaluator);
  EXPECT_FALSE(r.fidelity);
  EXPECT_EQ(to_json(r, c)["history"][0]["resolution"], "template");
}

TEST(Fidelity, AFineTemplateTheEngineRefusesNamesTheField) {
  try {
    testing::campaign({1000, 100}, {{"fidelity", {{"fine", {{"sample", {{"diameter", -1}}}}}}}});
    FAIL();
  } catch (const orch::RequestError& e) {
    EXPECT_EQ(e.field, "fidelity.fine");
  }
  try {
    testing::campaign({1000, 100},
                      {{"fidelity", {{"fine", {{"sample", {{"diameter", 12}}}}}, {"steps", 2}}}});
    FAIL();
  } catch (const orch::RequestError& e) {
    EXPECT_EQ(e.field, "fidelity.steps");
    EXPECT_STREQ(e.what(), "fidelity.steps: unknown field");
  }
}

}  // namespace
}  // namespace rockcal::calibration
