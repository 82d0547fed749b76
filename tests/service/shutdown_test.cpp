// Graceful shutdown: SIGTERM stops the server promptly, stops its running jobs, puts them back in
// the queue without counting an attempt, and the next start finishes them.
#include <gtest/gtest.h>
#include <stdlib.h>

#include "db/sqlite.hpp"
#include "support.hpp"

namespace rockcal::test {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

TEST(Shutdown, SigtermRequeuesRunningJobsAndRestartFinishesThem) {
  TempDir dir;
  setenv("FAKE_DEM_SLEEP", "3", 1);  // inherited by the server and its fake engine runs
  std::vector<std::string> options = {"--engine", fake_engine(), "--ranks-per-job",
                                      "0",        "--workers",   "1"};
  ServerProcess server(dir.path(), options);
  server.start();
  auto c = server.client();
  auto r =
      c.Post("/api/v1/campaigns", sweep_request({"uct"}, {31, 37}, {1}).dump(), "application/json");
  ASSERT_TRUE(r && r->status == 201);
  ASSERT_TRUE(poll_until(
      [&] { return get_json(c, "/api/v1/campaigns/1")["progress"]["running"] == 1; }, 10s));
  auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(server.terminate(), 0) << server.stderr_text();
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 8s);
  EXPECT_TRUE(processes_mentioning(dir.path().string()).empty()) << "a job outlived the server";
  {
    db::Connection conn(server.db().string());
    auto st = conn.prepare("SELECT state, attempts FROM jobs ORDER BY id");
    ASSERT_TRUE(st.step());
    EXPECT_EQ(st.text(0), "queued") << "the interrupted job goes back to the queue";
    EXPECT_EQ(st.int64(1), 0) << "a shutdown is not the job's failure";
  }
  setenv("FAKE_DEM_SLEEP", "0", 1);
  ServerProcess restarted(dir.path(), options);
  restarted.start();
  auto c2 = restarted.client();
  json done = wait_campaign(c2, 1, 30s);
  EXPECT_EQ(done["state"], "succeeded") << done.dump();
  EXPECT_EQ(restarted.terminate(), 0);
  unsetenv("FAKE_DEM_SLEEP");
}

}  // namespace
}  // namespace rockcal::test
