// Determinism: the same campaign asks for the same points, so a restarted campaign replays its
// history from the job cache and continues without re-running a finished evaluation.
#include <gtest/gtest.h>

#include <bit>

#include "orchestrator/calibration/driver.hpp"
#include "synthetic.hpp"

namespace rockcal::calibration {
namespace {

bool same_requests(const std::vector<EvaluationRequest>& a,
                   const std::vector<EvaluationRequest>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    // Bitwise: the job cache hashes the canonical job, so "close" would be a cache miss.
    if (std::bit_cast<std::uint64_t>(a[i].point.fr0_n) !=
            std::bit_cast<std::uint64_t>(b[i].point.fr0_n) ||
        std::bit_cast<std::uint64_t>(a[i].point.fs0_n) !=
            std::bit_cast<std::uint64_t>(b[i].point.fs0_n) ||
        a[i].sample_seed != b[i].sample_seed) {
      return false;
    }
  }
  return true;
}

struct Case {
  const char* name;
  testing::Model model;
  PeakLoads targets;
  nlohmann::json overrides;
};

class Replay : public ::testing::TestWithParam<int> {};

const std::vector<Case>& cases() {
  static const std::vector<Case> c = {
      {"ratio_scale", testing::power_law, testing::power_law({40, 90}), {{"seeds", {5, 6}}}},
      {"direct_2d_bobyqa", testing::non_homogeneous, testing::non_homogeneous({40, 90}), {}},
      {"sbplx_compromise",
       testing::smooth_min,
       {60000, 20000},
       {{"algorithm", "sbplx"}, {"strategy", "direct_2d"}}},
      {"crs2_random",
       testing::non_homogeneous,
       testing::non_homogeneous({40, 90}),
       {{"algorithm", "crs2_lm"}, {"random_seed", 7}}},
  };
  return c;
}

TEST_P(Replay, KilledCampaignReplaysFromCacheAndFinishesIdentically) {
  const Case& k = cases()[GetParam()];
  const CalibrationCampaign c = testing::campaign(k.targets, k.overrides);

  // The uninterrupted reference run.
  testing::ModelEvaluator reference_model(k.model);
  reference_model.noise = 0.003;
  const CalibrationReport reference = run_calibration(c, reference_model);
  ASSERT_GT(reference_model.log.size(), 8u) << k.name;

  // A run "killed" after 8 finished evaluations: its results stay in the job cache.
  testing::ModelEvaluator model(k.model);
  model.noise = 0.003;
  testing::CachingEvaluator cache(model);
  cache.cancel_after = 8;
  const CalibrationReport killed = run_calibration(c, cache);
  EXPECT_EQ(killed.stop_reason, StopReason::cancelled);
  const int finished = cache.fresh;

  // The restart: same campaign, same cache; nothing finished is run again.
  cache.cancel_after = -1;
  cache.fresh = 0;
  cache.log.clear();
  model.log.clear();
  const CalibrationReport restarted = run_calibration(c, cache);
  EXPECT_TRUE(same_requests(cache.log, reference_model.log)) << k.name;
  EXPECT_EQ(cache.fresh, int(reference_model.log.size()) - finished) << k.name;
  for (const EvaluationRequest& r : model.log) {
    for (std::size_t i = 0; i < std::size_t(finished); ++i) {
      EXPECT_FALSE(r.point == reference_model.log[i].point &&
                   r.sample_seed == reference_model.log[i].sample_seed)
          << k.name << ": re-ran finished evaluation " << i;
    }
  }
  EXPECT_EQ(restarted.history.size(), reference.history.size());
  ASSERT_TRUE(restarted.best && reference.best);
  EXPECT_EQ(restarted.best->point, reference.best->point);
  EXPECT_EQ(to_json(restarted, c).dump(), to_json(reference, c).dump());
}

INSTANTIATE_TEST_SUITE_P(Strategies, Replay, ::testing::Range(0, int(cases().size())),
                         [](const auto& info) { return std::string(cases()[info.param].name); });

}  // namespace
}  // namespace rockcal::calibration
