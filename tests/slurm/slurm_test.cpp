// The Slurm executor on a real Slurm (tests/slurm/run.sh starts a one-node cluster and sets
// SLURM_CONF): a UCT+BTT sweep run to completion by the real engine under srun, a campaign
// cancelled while jobs wait in Slurm's queue, a server killed with SIGKILL mid-sweep and
// restarted (it re-attaches; no job is submitted twice), and a job Slurm times out.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "db/sqlite.hpp"
#include "orchestrator/command.hpp"
#include "support.hpp"

namespace rockcal::test {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

struct SlurmJob {
  std::string id, name, state, reason, comment;
};

// Every job Slurm still knows (MinJobAge=3600 in the test cluster) whose directory is under `dir`.
std::vector<SlurmJob> slurm_jobs_under(const std::filesystem::path& dir) {
  auto r = orch::run_command({"squeue", "--noheader", "--states=all", "--format=%i|%j|%T|%r|%k"});
  EXPECT_TRUE(r.ok()) << r.err << r.error;
  std::vector<SlurmJob> out;
  std::istringstream in(r.out);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::size_t start = 0;
    for (int i = 0; i < 4; ++i) {
      auto bar = line.find('|', start);
      if (bar == std::string::npos) break;
      f.push_back(line.substr(start, bar - start));
      start = bar + 1;
    }
    if (f.size() != 4) continue;
    std::string comment = line.substr(start);
    while (!comment.empty() && comment.back() == ' ') comment.pop_back();
    if (comment.rfind(dir.string() + "/", 0) != 0) continue;
    out.push_back({f[0], f[1], f[2], f[3], comment});
  }
  return out;
}

struct StoredJob {
  std::int64_t id = 0;
  std::string state;
  std::optional<std::string> handle;
  int attempts = 0;
  std::string error;
};

std::vector<StoredJob> stored_jobs(const std::filesystem::path& db) {
  db::Connection conn(db.string());
  auto st =
      conn.prepare("SELECT id, state, handle, attempts, COALESCE(error, '') FROM jobs ORDER BY id");
  std::vector<StoredJob> out;
  while (st.step()) {
    out.push_back(
        {st.int64(0), st.text(1), st.opt_text(2), static_cast<int>(st.int64(3)), st.text(4)});
  }
  return out;
}

std::string metrics(httplib::Client& c) {
  auto r = c.Get("/metrics");
  return r ? r->body : "";
}

std::int64_t post_campaign(httplib::Client& c, const json& request) {
  auto r = c.Post("/api/v1/campaigns", request.dump(), "application/json");
  EXPECT_TRUE(r && r->status == 201) << (r ? r->body : "no response");
  return r ? json::parse(r->body)["id"].get<std::int64_t>() : 0;
}

std::vector<std::string> slurm_options(std::vector<std::string> more) {
  std::vector<std::string> o = {"--executor", "slurm", "--slurm-poll", "1"};
  o.insert(o.end(), more.begin(), more.end());
  return o;
}

TEST(Slurm, UctBttSweepRunsToCompletionWithTheRealEngine) {
  TempDir dir;
  ServerProcess server(dir.path(),
                       slurm_options({"--engine", engine_binary(), "--max-queued", "4"}));
  server.start();
  auto c = server.client();
  json request = sweep_request({"uct", "btt"}, {40, 80}, {50, 70});
  // A disc of diameter 6 keeps too few particles for the engine's BTT; 10 holds 41.
  request["job"]["sample"]["diameter"] = 10;
  auto id = post_campaign(c, request);
  json done = wait_campaign(c, id, 300s);
  std::string errors;
  for (const auto& j : stored_jobs(server.db())) errors += j.error + "\n";
  ASSERT_EQ(done["state"], "succeeded") << errors << server.stderr_text();
  EXPECT_EQ(done["progress"]["succeeded"], 8);

  json results = get_json(c, "/api/v1/campaigns/" + std::to_string(id) + "/results");
  std::set<std::tuple<std::string, double, double>> points;
  for (const auto& row : results["results"]) {
    EXPECT_EQ(row["state"], "succeeded");
    EXPECT_GT(row["peak_load"].get<double>(), 0) << row.dump();
    points.insert(
        {row["test"].get<std::string>(), row["fr0"].get<double>(), row["fs0"].get<double>()});
  }
  EXPECT_EQ(points.size(), 8u);

  // One Slurm job per rockcal job, COMPLETED, named and commented after it, with its marker. The
  // marker ends a job for rockcal while Slurm may still show it COMPLETING for a moment.
  std::vector<SlurmJob> in_slurm;
  EXPECT_TRUE(poll_until(
      [&] {
        in_slurm = slurm_jobs_under(server.data_dir());
        return std::all_of(in_slurm.begin(), in_slurm.end(),
                           [](const SlurmJob& j) { return j.state != "COMPLETING"; });
      },
      30s));
  EXPECT_EQ(in_slurm.size(), 8u);
  std::map<std::string, SlurmJob> by_id;
  for (const auto& j : in_slurm) by_id[j.id] = j;
  for (const auto& job : stored_jobs(server.db())) {
    ASSERT_TRUE(job.handle) << "job " << job.id;
    ASSERT_TRUE(by_id.count(*job.handle)) << "job " << job.id << " handle " << *job.handle;
    const auto& s = by_id[*job.handle];
    auto job_dir = server.data_dir() / "jobs" / std::to_string(job.id);
    EXPECT_EQ(s.state, "COMPLETED");
    EXPECT_EQ(s.name, "rockcal-" + std::to_string(job.id));
    EXPECT_EQ(s.comment, job_dir.string());
    std::ifstream marker(job_dir / "exit-status");
    int code = -1;
    marker >> code;
    EXPECT_EQ(code, 0);
    EXPECT_EQ(job.attempts, 1);
  }
  std::string m = metrics(c);
  EXPECT_NE(m.find("rockcal_executor_running{executor=\"slurm\"} 0\n"), std::string::npos) << m;
  EXPECT_EQ(m.find("rockcal_executor_failures_total{"), std::string::npos) << m;
  EXPECT_EQ(server.terminate(), 0);
}

TEST(Slurm, CancelStopsJobsRunningAndPendingInSlurmWithOneBatchedQuery) {
  TempDir dir;
  // Counts squeue runs: the executor must ask once for all jobs, not once per job.
  auto bin = dir.path() / "bin";
  std::filesystem::create_directories(bin);
  auto calls = dir.path() / "squeue.calls";
  std::ofstream(bin / "squeue") << "#!/bin/sh\necho \"$*\" >> '" << calls.string()
                                << "'\nexec /usr/bin/squeue \"$@\"\n";
  std::filesystem::permissions(bin / "squeue", std::filesystem::perms::owner_all);
  std::string path = getenv("PATH");
  setenv("PATH", (bin.string() + ":" + path).c_str(), 1);
  ServerProcess server(dir.path(), slurm_options({"--engine", fake_engine(), "--max-queued", "4"}));
  server.start();
  setenv("PATH", path.c_str(), 1);
  auto c = server.client();
  // fr0 = 17: the fake engine hangs. The node has 2 CPUs: two jobs run, two wait in Slurm.
  auto id = post_campaign(c, sweep_request({"uct"}, {17}, {1, 2, 3, 4}));
  auto campaign = "/api/v1/campaigns/" + std::to_string(id);
  ASSERT_TRUE(poll_until(
      [&] {
        std::map<std::string, int> states;
        for (const auto& j : slurm_jobs_under(server.data_dir())) ++states[j.state];
        json p = get_json(c, campaign)["progress"];
        return states["RUNNING"] == 2 && states["PENDING"] == 2 && p["running"] == 2 &&
               p["queued"] == 2;
      },
      60s))
      << get_json(c, campaign).dump(2);
  std::string m = metrics(c);
  EXPECT_NE(m.find("rockcal_executor_pending{executor=\"slurm\"} 2\n"), std::string::npos) << m;
  EXPECT_NE(m.find("rockcal_executor_running{executor=\"slurm\"} 2\n"), std::string::npos) << m;
  EXPECT_NE(m.find("rockcal_executor_queue_depth{executor=\"slurm\"} 0\n"), std::string::npos) << m;

  auto count_calls = [&] {
    std::ifstream in(calls);
    std::string line;
    int n = 0, widest = 0;
    while (std::getline(in, line)) {
      auto at = line.find("--jobs=");
      if (at == std::string::npos) continue;
      ++n;
      auto list = line.substr(at + 7, line.find(' ', at) - at - 7);
      widest = std::max(widest, 1 + static_cast<int>(std::count(list.begin(), list.end(), ',')));
    }
    return std::pair{n, widest};
  };
  auto before = count_calls();
  std::this_thread::sleep_for(5s);
  auto after = count_calls();
  // Four workers poll every second; one query a second answers all of them.
  EXPECT_LE(after.first - before.first, 7) << "squeue runs in 5 s";
  EXPECT_GE(after.first - before.first, 3) << "squeue runs in 5 s";
  EXPECT_EQ(after.second, 4) << "one query names all four jobs";

  auto del = c.Delete(campaign);
  ASSERT_TRUE(del && del->status == 200) << (del ? del->body : "");
  ASSERT_TRUE(poll_until(
      [&] {
        auto jobs = slurm_jobs_under(server.data_dir());
        return jobs.size() == 4 && std::all_of(jobs.begin(), jobs.end(), [](const SlurmJob& j) {
                 return j.state == "CANCELLED";
               });
      },
      60s));
  for (const auto& job : stored_jobs(server.db())) EXPECT_EQ(job.state, "cancelled");
  auto jobs_dir = (server.data_dir() / "jobs").string();
  EXPECT_TRUE(poll_until([&] { return processes_mentioning(jobs_dir).empty(); }, 30s))
      << "fake engine runs left behind";
  EXPECT_EQ(get_json(c, campaign)["state"], "cancelled");
  EXPECT_EQ(server.terminate(), 0);
}

TEST(Slurm, KillNineMidSweepThenRestartReattachesAndNeverSubmitsTwice) {
  TempDir dir;
  auto options = slurm_options({"--engine", engine_binary(), "--max-queued", "3"});
  ServerProcess server(dir.path(), options);
  server.start();
  auto c = server.client();
  // Strengths whose runs all peak at this fixed speed (at F_s0/F_r0 above 2 the cylinder hardens
  // after its bonds fail and may reach max_strain first: (40, 90) did, with the engine's
  // round-off).
  json request = sweep_request({"uct"}, {40, 80}, {50, 60, 70});
  request["job"]["sample"] = {{"diameter", 16}, {"height", 32}, {"radius", 1}};
  request["job"]["loading"]["platen_velocity"] = 0.02;
  auto id = post_campaign(c, request);
  auto campaign = "/api/v1/campaigns/" + std::to_string(id);

  // Crash with some jobs done, some in Slurm and some not yet submitted.
  std::map<std::int64_t, std::string> in_slurm_at_crash;
  ASSERT_TRUE(poll_until(
      [&] {
        json p = get_json(c, campaign)["progress"];
        if (p["succeeded"].get<int>() < 1) return false;
        in_slurm_at_crash.clear();
        int waiting = 0;
        for (const auto& j : stored_jobs(server.db())) {
          if (j.handle && (j.state == "running" || j.state == "queued")) {
            in_slurm_at_crash[j.id] = *j.handle;
          }
          waiting += j.state == "queued" && !j.handle;
        }
        return !in_slurm_at_crash.empty() && waiting > 0;
      },
      180s))
      << get_json(c, campaign).dump(2);
  server.kill9();

  ServerProcess restarted(dir.path(), options);
  restarted.start();
  EXPECT_NE(restarted.stderr_text().find("re-attached to"), std::string::npos)
      << restarted.stderr_text();
  auto c2 = restarted.client();
  json done = wait_campaign(c2, id, 300s);
  ASSERT_EQ(done["state"], "succeeded") << done.dump(2) << restarted.stderr_text();
  EXPECT_EQ(done["progress"]["succeeded"], 6);

  json results = get_json(c2, campaign + "/results");
  std::set<std::pair<double, double>> points;
  for (const auto& row : results["results"]) {
    EXPECT_EQ(row["state"], "succeeded");
    points.insert({row["fr0"].get<double>(), row["fs0"].get<double>()});
  }
  EXPECT_EQ(results["results"].size(), 6u);
  EXPECT_EQ(points.size(), 6u);

  // Never submitted twice: one Slurm job per rockcal job, and the ones in Slurm at the crash kept
  // their Slurm job.
  std::map<std::string, int> per_dir;
  for (const auto& j : slurm_jobs_under(restarted.data_dir())) ++per_dir[j.comment];
  EXPECT_EQ(per_dir.size(), 6u);
  for (const auto& [d, n] : per_dir) EXPECT_EQ(n, 1) << d << " submitted " << n << " times";
  for (const auto& job : stored_jobs(restarted.db())) {
    EXPECT_EQ(job.attempts, 1) << "job " << job.id;
    if (in_slurm_at_crash.count(job.id)) {
      EXPECT_EQ(job.handle, in_slurm_at_crash[job.id]) << "job " << job.id;
    }
  }
  db::Connection conn(restarted.db().string());
  auto st = conn.prepare("PRAGMA integrity_check");
  ASSERT_TRUE(st.step());
  EXPECT_EQ(st.text(0), "ok");
  EXPECT_EQ(restarted.terminate(), 0);
}

TEST(Slurm, AJobSlurmTimesOutEndsFailedWithTheReason) {
  TempDir dir;
  ServerProcess server(dir.path(), slurm_options({"--engine", fake_engine(), "--time-limit", "1",
                                                  "--retries", "0"}));
  server.start();
  auto c = server.client();
  auto id = post_campaign(c, sweep_request({"uct"}, {17}, {1}));  // hangs until Slurm stops it
  std::string handle;
  ASSERT_TRUE(poll_until(
      [&] {
        auto jobs = stored_jobs(server.db());
        if (jobs.size() == 1 && jobs[0].handle) handle = *jobs[0].handle;
        return !handle.empty();
      },
      30s));
  // Slurm's limit is whole minutes and it checks them every 30 s: about 60-90 s.
  json done = wait_campaign(c, id, 200s);
  ASSERT_EQ(done["state"], "failed") << done.dump(2);
  auto jobs = stored_jobs(server.db());
  ASSERT_EQ(jobs.size(), 1u);
  EXPECT_EQ(jobs[0].state, "failed");
  EXPECT_EQ(jobs[0].attempts, 1);
  EXPECT_EQ(jobs[0].error.rfind("Slurm job " + handle + " ended TIMEOUT (TimeLimit)", 0), 0u)
      << jobs[0].error;
  std::string m = metrics(c);
  EXPECT_NE(m.find("rockcal_executor_failures_total{executor=\"slurm\",reason=\"timeout\"} 1\n"),
            std::string::npos)
      << m;
  EXPECT_EQ(server.terminate(), 0);
}

}  // namespace
}  // namespace rockcal::test
