// One benchmark rock at small size on the real engine: the granite's own request
// (examples/rocks/lac_du_bonnet_granite.json: UCS/BTS 22.7, UCS/E 0.003, the auto platen speed) on
// a D/R 8 specimen with a small budget. What a user relies on: the campaign ends with a verdict,
// every run was quasi-static by the measure it reports, and the predicted loads meet the targets
// within the tolerance or else the verdict names the cause its own fields show.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "engine_runner.hpp"
#include "orchestrator/calibration/driver.hpp"
#include "orchestrator/calibration/runner_evaluator.hpp"

namespace rockcal::calibration {
namespace {

using nlohmann::json;

// The request at D/R `size`: the model cylinder D = size, H = 2 size, and the lab core mapped onto
// it (one model particle is D_lab / size of the lab's length), so the model-unit targets keep the
// rock's UCS/E.
json at_small_size(json request, double size, int runs) {
  request["job"]["sample"]["diameter"] = size;
  request["job"]["sample"]["height"] = 2 * size;
  json& lab = request["targets"]["lab"];
  lab["material"]["grain_radius"] = lab["specimen"]["diameter"].get<double>() / size;
  request["max_evaluations"] = runs;
  return request;
}

TEST(RockBenchmark, TheGraniteAtSmallSizeEndsWithAVerdictFromQuasiStaticRuns) {
  setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 0);
  setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 0);
  std::ifstream file(ROCKCAL_SOURCE_DIR "/examples/rocks/lac_du_bonnet_granite.json");
  ASSERT_TRUE(file) << "examples/rocks/lac_du_bonnet_granite.json";
  const json request = at_small_size(json::parse(file), 8, 20);
  const CalibrationCampaign c = parse_calibration_campaign(request);

  testing::EngineRunner engine;
  engine.engine = ROCKCAL_DEM;
  engine.work_dir =
      std::filesystem::temp_directory_path() / ("rockcal-rock-" + std::to_string(getpid()));
  RunnerEvaluator evaluator(engine, request["job"]);
  const CalibrationReport r = run_calibration(c, evaluator);
  std::filesystem::remove_all(engine.work_dir);
  std::printf("granite at D/R 8: %zu evaluations, verdict %s: %s\n", r.history.size(),
              to_string(r.verdict), r.verdict_reason.c_str());

  // Ends with a verdict from a posterior.
  ASSERT_TRUE(r.posterior) << r.verdict_reason;
  ASSERT_TRUE(r.verdict == Verdict::feasible || r.verdict == Verdict::compromise)
      << to_string(r.verdict) << ": " << r.verdict_reason;
  EXPECT_LE(r.history.size(), 20u + 2u) << "the budget and its check batch";

  // Runs that reached a peak were quasi-static by their own measure; runs without a peak (still
  // loading up past the bond-controlled window at large F_s0 / F_r0) are counted in the verdict.
  int runs = 0, peaks = 0, quasi_static = 0;
  for (const EvaluationRecord& e : r.history) {
    ASSERT_TRUE(e.uct && e.btt) << "evaluation " << e.index << ": " << e.error;
    for (const orch::Ensemble* test : {&*e.uct, &*e.btt}) {
      for (const orch::Realisation& x : test->realisations) {
        ++runs;
        if (!x.peak_load_n) continue;
        ++peaks;
        ASSERT_TRUE(x.quasi_static.has_value()) << "evaluation " << e.index;
        quasi_static += *x.quasi_static ? 1 : 0;
      }
    }
  }
  EXPECT_GT(peaks, runs / 2);
  // At this small size a few peaks may still come early; they are at most a tenth, and the
  // verdict counts them.
  EXPECT_GE(10 * quasi_static, 9 * peaks) << "peaks that were not quasi-static at the auto speed";
  if (quasi_static < peaks) {
    const std::string fast = std::to_string(peaks - quasi_static) + " of " + std::to_string(peaks) +
                             " runs that reported it were not quasi-static";
    EXPECT_NE(r.verdict_reason.find(fast), std::string::npos) << r.verdict_reason;
  } else {
    EXPECT_EQ(r.verdict_reason.find("not quasi-static"), std::string::npos) << r.verdict_reason;
  }
  if (peaks < runs) {
    const std::string no_peak =
        std::to_string(runs - peaks) + " of " + std::to_string(runs) + " runs ended without a peak";
    EXPECT_NE(r.verdict_reason.find(no_peak), std::string::npos) << r.verdict_reason;
  }

  // The loads within the tolerance, or the cause the fields show, named in the verdict.
  const PosteriorSummary& p = *r.posterior;
  if (r.verdict == Verdict::feasible) {
    EXPECT_LE(std::abs(p.uct.relative_error), c.tolerance);
    EXPECT_LE(std::abs(p.btt.relative_error), c.tolerance);
    return;
  }
  const bool ratio_out = r.ratio && !r.ratio->target_inside();
  if (ratio_out) {
    EXPECT_NE(r.verdict_reason.find("load ratio"), std::string::npos) << r.verdict_reason;
  } else if (!p.bounds_reached.empty()) {
    EXPECT_NE(r.verdict_reason.find(p.bounds_reached.front()), std::string::npos)
        << r.verdict_reason;
  } else if (r.stop_reason == StopReason::budget_exhausted) {
    EXPECT_NE(r.verdict_reason.find("budget"), std::string::npos) << r.verdict_reason;
  } else {
    EXPECT_NE(r.verdict_reason.find("cannot meet both loads"), std::string::npos)
        << r.verdict_reason;
  }
}

}  // namespace
}  // namespace rockcal::calibration
