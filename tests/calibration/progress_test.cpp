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
  EXPECT_EQ(progress_model_json(3, traced_campaign(), {10.0, {}, 0}, false), json::parse(R"({
    "unit": "evaluations", "done": 3, "budget": 64,
    "parts": [{"name": "search", "budget": 40}, {"name": "valley trace", "budget": 24}],
    "seed_reruns": 2, "left": 63, "fraction": 0.046875, "eta_seconds": 630.0})"));
  // Without a trace the budget is the search's alone.
  const json plain = progress_model_json(
      3, testing::campaign({2000, 300}, {{"consistency_evaluations", 0}}), {}, false);
  EXPECT_EQ(plain["budget"], 40);
  EXPECT_EQ(plain["parts"], json::parse(R"([{"name": "search", "budget": 40}])"));
  EXPECT_EQ(plain["seed_reruns"], 0);
  EXPECT_EQ(plain["eta_seconds"], nullptr) << "no pace measured yet";
}

TEST(ProgressModel, NeverBackwardsNeverEtaZeroWhileSomethingIsLeft) {
  const CalibrationCampaign c = traced_campaign();
  double last = 0.0;
  for (std::size_t n = 0; n <= 70; ++n) {
    const json m = progress_model_json(n, c, {0.01, {}, 0}, false);  // cached replays: 10 ms each
    EXPECT_GE(m["fraction"].get<double>(), last) << n;
    EXPECT_LE(m["fraction"].get<double>(), 1.0) << n;
    last = m["fraction"].get<double>();
    EXPECT_EQ(m["eta_seconds"], 1.0) << n << ": the re-runs are still left";
  }
  const json done = progress_model_json(30, c, {10.0, {}, 0}, true);  // ended early: tolerance met
  EXPECT_EQ(done["fraction"], 1.0);
  EXPECT_EQ(done["left"], 0);
  EXPECT_EQ(done["eta_seconds"], 0.0);
}

// A fine run costs tens of search evaluations: the ETA counts each part's evaluations left at its
// own pace, the fine runs' before one has ended at the search's times (r / r_fine)^4, and says
// none when that is unknown (a coarse pace alone once promised 34 s with 25 minutes left).
TEST(ProgressModel, TheFineRunsLeftCountAtTheirOwnPace) {
  auto with_fine = [](nlohmann::json fine_sample, nlohmann::json radius = 2) {
    return testing::campaign(
        {2000, 300},
        {{"strategy", "bayes"},
         {"max_evaluations", 40},
         {"job", {{"sample", {{"radius", radius}}}}},
         {"fidelity",
          {{"fine", {{"sample", fine_sample}}}, {"strength_scale", 0.5}, {"runs", 6}}}});
  };
  const CalibrationCampaign c = with_fine({{"radius", 1}});
  EXPECT_EQ(fine_cost_ratio(c), 16.0);
  json m = progress_model_json(3, c, {10.0, {}, 0}, false);
  EXPECT_EQ(m["budget"], 46);
  EXPECT_EQ(m["eta_seconds"], 37 * 10.0 + 6 * 160.0);
  // The search spent, two fine runs timed at 300 s each: the four left at that pace.
  m = progress_model_json(42, c, {10.0, 300.0, 2}, false);
  EXPECT_EQ(m["eta_seconds"], 4 * 300.0);
  // The search answered after 30 evaluations: its unspent budget is not waited for.
  m = progress_model_json(31, c, {10.0, 300.0, 1}, false);
  EXPECT_EQ(m["eta_seconds"], 5 * 300.0);
  // Another size at the same radius: the particles' count.
  EXPECT_DOUBLE_EQ(*fine_cost_ratio(with_fine({{"diameter", 15}})), 1.5 * 1.5);
  // A template that leaves the radius to the engine's default: no ratio, no ETA until timed.
  const CalibrationCampaign unknown = with_fine({{"radius", 1}}, nullptr);
  EXPECT_FALSE(fine_cost_ratio(unknown));
  EXPECT_EQ(progress_model_json(3, unknown, {10.0, {}, 0}, false)["eta_seconds"], nullptr);
  EXPECT_EQ(progress_model_json(42, unknown, {10.0, 250.0, 2}, false)["eta_seconds"], 1000.0);
  EXPECT_EQ(progress_model_json(46, unknown, {10.0, 250.0, 6}, true)["eta_seconds"], 0.0);
}

}  // namespace
}  // namespace rockcal::calibration
