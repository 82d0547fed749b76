// Crash recovery: kill -9 the real server in the middle of a sweep run by the real engine
// under mpirun, restart it on the same file: the orphaned mpirun process groups are found and
// stopped, the running jobs re-queued, the sweep finishes with exactly one result per point, no
// process is left behind, and PRAGMA integrity_check says ok.
#include <gtest/gtest.h>

#include <set>

#include "db/sqlite.hpp"
#include "orchestrator/process_groups.hpp"
#include "support.hpp"

namespace rockcal::test {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

std::vector<pid_t> running_job_groups(const std::filesystem::path& db) {
  db::Connection conn(db.string());
  auto st = conn.prepare("SELECT handle FROM jobs WHERE state = 'running' AND handle IS NOT NULL");
  std::vector<pid_t> out;
  while (st.step()) out.push_back(std::stoi(st.text(0)));
  return out;
}

TEST(Recovery, KillNineMidSweepThenRestartFinishesWithOneResultPerPoint) {
  TempDir dir;
  std::vector<std::string> options = {"--engine", engine_binary(), "--ranks-per-job",
                                      "1",        "--workers",     "2"};
  ServerProcess server(dir.path(), options);
  server.start();
  auto c = server.client();
  // Jobs long enough (about 1 s of loop each; D = 12 at the default speed took 0.1 s) that the
  // crash finds some running: with shorter ones a job could finish between the poll and the kill.
  json request = sweep_request({"uct"}, {40, 80}, {50, 70, 90});
  request["job"]["sample"] = {{"diameter", 16}, {"height", 32}, {"radius", 1}};
  request["job"]["loading"]["platen_velocity"] = 0.02;
  auto r = c.Post("/api/v1/campaigns", request.dump(), "application/json");
  ASSERT_TRUE(r && r->status == 201);
  auto id = json::parse(r->body)["id"].get<std::int64_t>();

  // Crash while some jobs are done and others are running (with their pgid recorded).
  std::vector<pid_t> orphans;
  ASSERT_TRUE(poll_until(
      [&] {
        json p = get_json(c, "/api/v1/campaigns/" + std::to_string(id))["progress"];
        if (p["succeeded"].get<int>() < 1 || p["queued"].get<int>() < 1) return false;
        orphans = running_job_groups(server.db());
        return !orphans.empty();
      },
      60s))
      << "never saw the sweep half done";
  server.kill9();
  bool any_orphan_alive = false;
  for (pid_t g : orphans) any_orphan_alive |= orch::group_runs_engine(g, "rockcal-dem");
  EXPECT_TRUE(any_orphan_alive) << "the crash should leave running mpirun groups behind";

  ServerProcess restarted(dir.path(), options);
  restarted.start();
  for (pid_t g : orphans) {
    EXPECT_TRUE(orch::group_members(g).empty()) << "orphaned group " << g << " still runs";
  }
  EXPECT_NE(restarted.stderr_text().find("re-queued"), std::string::npos)
      << restarted.stderr_text();
  auto c2 = restarted.client();
  json done = wait_campaign(c2, id, 120s);
  // Every point ends with its run's result: a peak, or a run that reached none (the engine's
  // physics decides which, e.g. a UCT that hardens to loading.max_strain), which is a failed job
  // "no peak: ..." with its result kept. Nothing else may fail.
  EXPECT_EQ(done["progress"]["succeeded"].get<int>() + done["progress"]["failed"].get<int>(), 6)
      << done.dump(2);

  json results = get_json(c2, "/api/v1/campaigns/" + std::to_string(id) + "/results");
  std::set<std::pair<double, double>> points;
  int no_peak = 0;
  for (const auto& row : results["results"]) {
    if (row["state"] == "failed" && row["error"].get<std::string>().rfind("no peak: ", 0) == 0) {
      ++no_peak;
    } else {
      EXPECT_EQ(row["state"], "succeeded") << row.dump();
      EXPECT_TRUE(row["peak_load"].is_number()) << row.dump();
    }
    points.insert({row["fr0"].get<double>(), row["fs0"].get<double>()});
  }
  EXPECT_LT(no_peak, 6) << "the sweep should measure some peaks";
  EXPECT_EQ(results["results"].size(), 6u);
  EXPECT_EQ(points.size(), 6u);
  EXPECT_EQ(restarted.terminate(), 0);

  db::Connection conn(restarted.db().string());
  auto count = conn.prepare("SELECT COUNT(*), COUNT(DISTINCT hash) FROM results");
  ASSERT_TRUE(count.step());
  EXPECT_EQ(count.int64(0), 6) << "exactly one result per point";
  EXPECT_EQ(count.int64(1), 6);
  auto jobs = conn.prepare(
      "SELECT COUNT(*) FROM jobs WHERE state <> 'succeeded' AND NOT (state = 'failed' AND "
      "error LIKE 'no peak: %')");
  ASSERT_TRUE(jobs.step());
  EXPECT_EQ(jobs.int64(0), 0);
  auto kept = conn.prepare("SELECT COUNT(*) FROM results WHERE no_peak IS NOT NULL");
  ASSERT_TRUE(kept.step());
  EXPECT_EQ(kept.int64(0), no_peak) << "a run without a peak keeps its result, once";
  auto check = conn.prepare("PRAGMA integrity_check");
  ASSERT_TRUE(check.step());
  EXPECT_EQ(check.text(0), "ok");
  EXPECT_TRUE(processes_mentioning(dir.path().string()).empty()) << "processes left running";
}

}  // namespace
}  // namespace rockcal::test
