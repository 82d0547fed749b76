// A calibration's progress model, the one count the CLI and the dashboard show: the whole budget
// with its parts named, the seed re-runs beside it, what is left, a fraction that never goes
// backwards and reaches 1 when the report is in, and an ETA never 0 while something is left.
#include <gtest/gtest.h>

#include "orchestrator/calibration/progress.hpp"
#include "synthetic.hpp"

namespace rockcal::calibration {
namespace {

using nlohmann::json;

CalibrationCampaign traced_campaign() {
  return testing::campaign(
      {2000, 300}, {{"max_evaluations", 40}, {"consistency_evaluations", 24}, {"seeds", {2, 3}}});
}

TEST(ProgressModel, TheBudgetItsPartsWhatIsLeftAndTheEtaAtThePace) {
  EXPECT_EQ(progress_model_json(3, traced_campaign(), 10.0, false), json::parse(R"({
    "unit": "evaluations", "done": 3, "budget": 64,
    "parts": [{"name": "search", "budget": 40}, {"name": "valley trace", "budget": 24}],
    "seed_reruns": 2, "left": 63, "fraction": 0.046875, "eta_seconds": 630.0})"));
  // Without a trace the budget is the search's alone.
  const json plain = progress_model_json(
      3, testing::campaign({2000, 300}, {{"consistency_evaluations", 0}}), std::nullopt, false);
  EXPECT_EQ(plain["budget"], 40);
  EXPECT_EQ(plain["parts"], json::parse(R"([{"name": "search", "budget": 40}])"));
  EXPECT_EQ(plain["seed_reruns"], 0);
  EXPECT_EQ(plain["eta_seconds"], nullptr) << "no pace measured yet";
}

TEST(ProgressModel, NeverBackwardsNeverEtaZeroWhileSomethingIsLeft) {
  const CalibrationCampaign c = traced_campaign();
  double last = 0.0;
  for (std::size_t n = 0; n <= 70; ++n) {
    const json m = progress_model_json(n, c, 0.01, false);  // cached replays: 10 ms each
    EXPECT_GE(m["fraction"].get<double>(), last) << n;
    EXPECT_LE(m["fraction"].get<double>(), 1.0) << n;
    last = m["fraction"].get<double>();
    EXPECT_EQ(m["eta_seconds"], 1.0) << n << ": the re-runs are still left";
  }
  const json done = progress_model_json(30, c, 10.0, true);  // ended early: tolerance met
  EXPECT_EQ(done["fraction"], 1.0);
  EXPECT_EQ(done["left"], 0);
  EXPECT_EQ(done["eta_seconds"], 0.0);
}

}  // namespace
}  // namespace rockcal::calibration
