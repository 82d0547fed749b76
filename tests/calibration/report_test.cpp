// The report JSON: the fields the API and users rely on, and no NaN anywhere.
#include <gtest/gtest.h>

#include "orchestrator/calibration/driver.hpp"
#include "synthetic.hpp"

namespace rockcal::calibration {
namespace {

using nlohmann::json;

bool has_nan(const json& j) {
  if (j.is_number_float()) return !std::isfinite(j.get<double>());
  if (j.is_structured()) {
    for (const json& v : j) {
      if (has_nan(v)) return true;
    }
  }
  return false;
}

TEST(Report, CarriesBestTargetsHistoryRatioAndScatter) {
  const CalibrationCampaign c =
      testing::campaign(testing::power_law({40, 90}), {{"seeds", {8, 9}}});
  testing::ModelEvaluator evaluator(testing::power_law);
  evaluator.failure_rate = 0.15;
  const CalibrationReport r = run_calibration(c, evaluator);
  const json j = to_json(r, c);
  EXPECT_FALSE(has_nan(j));
  EXPECT_EQ(j["kind"], "calibration");
  EXPECT_EQ(j["verdict"], "feasible");
  EXPECT_EQ(j["stop_reason"], "tolerance_met");
  EXPECT_TRUE(j["best"]["fr0"].is_number());
  EXPECT_TRUE(j["best"]["fs0"].is_number());
  EXPECT_TRUE(j["best"]["uct"]["peak_load"].is_number());
  EXPECT_TRUE(j["best"]["btt"]["peak_load"].is_number());
  EXPECT_LE(std::abs(j["best"]["btt"]["relative_error"].get<double>()), 0.02);
  EXPECT_FALSE(j["best"].contains("lab"));  // model-unit targets
  EXPECT_EQ(j["history"].size(), r.history.size());
  EXPECT_EQ(j["evaluations"], r.history.size());
  // The convergence curve never rises.
  double previous = INFINITY;
  for (const json& row : j["history"]) {
    if (row["best_misfit_so_far"].is_null()) continue;
    EXPECT_LE(row["best_misfit_so_far"].get<double>(), previous);
    previous = row["best_misfit_so_far"].get<double>();
  }
  EXPECT_TRUE(j["ratio"]["target_inside"].get<bool>());
  EXPECT_LE(j["ratio"]["min"].get<double>(), j["ratio"]["max"].get<double>());
  EXPECT_EQ(j["scatter"]["runs"].size(), 3u);
  EXPECT_TRUE(j["homogeneity"]["holds"].get<bool>());
  EXPECT_EQ(j["strategy"]["used"], "ratio_scale");
}

TEST(Report, AllFailedEvaluationsGiveFailedVerdictAndValidJson) {
  const CalibrationCampaign c = testing::campaign({1000, 100}, {{"max_evaluations", 8}});
  testing::ModelEvaluator evaluator(testing::power_law);
  evaluator.failure_rate = 1.0;
  const CalibrationReport r = run_calibration(c, evaluator);
  EXPECT_EQ(r.verdict, Verdict::failed);
  EXPECT_EQ(r.history.size(), 8u);
  const json j = to_json(r, c);
  EXPECT_FALSE(has_nan(j));
  EXPECT_TRUE(j["best"].is_null());
  EXPECT_TRUE(j["ratio"].is_null());
  EXPECT_FALSE(j["homogeneity"]["holds"].get<bool>());
  EXPECT_TRUE(j["homogeneity"]["checks"][0]["exponent_uct"].is_null());
}

}  // namespace
}  // namespace rockcal::calibration
