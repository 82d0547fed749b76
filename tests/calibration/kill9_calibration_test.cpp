// Crash recovery of a calibration: kill -9 the real `rockcal serve` in the middle of a calibration,
// restart it on the same database: the campaign finishes, and no evaluation that had finished
// before the crash runs again (its jobs are answered from the store, the optimiser replays its
// history). The engine is the power-law formula script, so the test is about the service, not the
// physics.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>

#include "synthetic.hpp"
#include "tests/service/support.hpp"

namespace rockcal::test {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

std::map<std::string, int> engine_runs(const std::filesystem::path& file) {
  std::map<std::string, int> times;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) ++times[line];
  return times;
}

TEST(CalibrationRecovery, KillNineMidCalibrationResumesWithoutRerunningFinishedEvaluations) {
  TempDir dir;
  const auto runs_file = dir.path() / "engine-runs.txt";
  setenv("FAKE_DEM_RUNS", runs_file.c_str(), 1);  // inherited by the server and its engine runs
  const std::vector<std::string> options = {"--engine", FAKE_DEM,    "--ranks-per-job",
                                            "0",        "--workers", "2"};
  ServerProcess server(dir.path(), options);
  server.start();
  auto c = server.client();
  json request = calibration::testing::campaign_json(calibration::testing::power_law({40, 90}),
                                                     {{"name", "kill -9 twin"}});
  request["strategy"] = "direct_2d";  // about 20 evaluations: room to crash in the middle
  auto r = c.Post("/api/v1/campaigns", request.dump(), "application/json");
  ASSERT_TRUE(r && r->status == 201) << (r ? r->body : "no response");
  const auto id = json::parse(r->body)["id"].get<std::int64_t>();
  const std::string path = "/api/v1/campaigns/" + std::to_string(id);

  ASSERT_TRUE(
      poll_until([&] { return get_json(c, path)["progress"]["succeeded"].get<int>() >= 12; }, 60s))
      << "the calibration never got going";
  server.kill9();
  const auto before = engine_runs(runs_file);

  ServerProcess restarted(dir.path(), options);
  restarted.start();
  auto c2 = restarted.client();
  json done = wait_campaign(c2, id, 120s);
  ASSERT_EQ(done["state"], "succeeded") << done.dump(2);
  ASSERT_TRUE(done["best"].is_object()) << done.dump(2);
  EXPECT_NEAR(done["best"]["fr0"].get<double>() / 40, 1.0, 0.1);
  EXPECT_NEAR(done["best"]["fs0"].get<double>() / 90, 1.0, 0.1);

  const auto after = engine_runs(runs_file);
  int repeated = 0, new_points = 0;
  for (const auto& [line, n] : after) {
    repeated += n - 1;
    new_points += before.count(line) ? 0 : 1;
  }
  // Only jobs running at the crash (2 workers) may run again; everything else came from the store.
  EXPECT_LE(repeated, 2);
  EXPECT_GT(new_points, 0) << "the restarted campaign should have continued, not stopped";
  std::printf(
      "kill -9 calibration: %zu distinct engine runs before the crash, %zu in all, %d re-run\n",
      before.size(), after.size(), repeated);
  EXPECT_EQ(restarted.terminate(), 0);
  EXPECT_TRUE(processes_mentioning(dir.path().string()).empty()) << "processes left running";
}

}  // namespace
}  // namespace rockcal::test
