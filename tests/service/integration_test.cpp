// Acceptance of the service: the real `rockcal serve` on a free loopback port with a temporary
// database and the real rockcal-dem under mpirun runs a 2x2 sweep of UCT and BTT over HTTP; the 8
// results, the CSV export and the cache (a resubmission runs no new job) are checked, and the CLI
// client is driven against the same server.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include "support.hpp"

namespace rockcal::test {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

// Runs the rockcal CLI; returns (exit status, stdout).
std::pair<int, std::string> run_cli(const std::string& args) {
  std::string cmd = rockcal_binary() + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  while (std::size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
  int status = pclose(p);
  return {WEXITSTATUS(status), out};
}

std::size_t job_dirs(const std::filesystem::path& data_dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(data_dir / "jobs")) ++n;
  return n;
}

TEST(Acceptance, TwoByTwoSweepOfUctAndBttOverHttpWithRealEngine) {
  TempDir dir;
  ServerProcess server(dir.path(),
                       {"--engine", engine_binary(), "--ranks-per-job", "1", "--workers", "2"});
  server.start();
  auto c = server.client();
  // Points where the tiny UCT and BTT both break to a peak: at (50, 90) the UCT hardens to
  // loading.max_strain, a run without a peak (a failed job, tested with the fake engine).
  json request = sweep_request({"uct", "btt"}, {50, 80}, {50, 70});
  auto r = c.Post("/api/v1/campaigns", request.dump(), "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  auto id = json::parse(r->body)["id"].get<std::int64_t>();

  json done = wait_campaign(c, id, 120s);
  ASSERT_EQ(done["state"], "succeeded") << done.dump(2) << server.stderr_text();
  EXPECT_EQ(done["progress"]["total"], 8);
  EXPECT_EQ(done["progress"]["succeeded"], 8);
  EXPECT_EQ(done["progress"]["cached"], 0);

  json results = get_json(c, "/api/v1/campaigns/" + std::to_string(id) + "/results");
  ASSERT_EQ(results["results"].size(), 8u);
  std::set<std::tuple<std::string, double, double>> points;
  for (const auto& row : results["results"]) {
    points.insert(
        {row["test"].get<std::string>(), row["fr0"].get<double>(), row["fs0"].get<double>()});
    EXPECT_EQ(row["state"], "succeeded");
    EXPECT_GT(row["peak_load"].get<double>(), 0) << row.dump();
    EXPECT_GT(row["strength"].get<double>(), 0) << row.dump();
    EXPECT_GT(row["particles"].get<std::int64_t>(), 0) << row.dump();
    if (row["test"] == "uct") {
      EXPECT_GT(row["youngs_modulus"].get<double>(), 0) << row.dump();
    }
  }
  EXPECT_EQ(points.size(), 8u) << "one result per (test, fr0, fs0)";

  auto csv = c.Get("/api/v1/campaigns/" + std::to_string(id) + "/results?format=csv");
  ASSERT_TRUE(csv);
  std::istringstream lines(csv->body);
  std::string header, line;
  std::getline(lines, header);
  EXPECT_EQ(header,
            "fr0_n,fs0_n,test,peak_load_n,strength_pa,youngs_modulus_pa,particles,wall_seconds,"
            "state,job_id,seed,error");
  int rows = 0;
  while (std::getline(lines, line)) {
    ++rows;
    EXPECT_NE(line.find(",succeeded,"), std::string::npos) << line;
  }
  EXPECT_EQ(rows, 8);

  std::int64_t first_job = results["results"][0]["job_id"];
  auto curve = c.Get("/api/v1/jobs/" + std::to_string(first_job) + "/curve");
  ASSERT_TRUE(curve);
  EXPECT_EQ(curve->status, 200);
  EXPECT_GT(std::count(curve->body.begin(), curve->body.end(), '\n'), 10);

  // Resubmitting the same sweep runs nothing: every point is answered from the store.
  std::size_t dirs_before = job_dirs(server.data_dir());
  auto again = c.Post("/api/v1/campaigns", request.dump(), "application/json");
  ASSERT_TRUE(again && again->status == 201);
  auto id2 = json::parse(again->body)["id"].get<std::int64_t>();
  json cached = get_json(c, "/api/v1/campaigns/" + std::to_string(id2));
  EXPECT_EQ(cached["state"], "succeeded") << "answered at once, nothing queued";
  EXPECT_EQ(cached["progress"]["cached"], 8);
  EXPECT_EQ(job_dirs(server.data_dir()), dirs_before) << "no job directory = no run";
  json results2 = get_json(c, "/api/v1/campaigns/" + std::to_string(id2) + "/results");
  for (std::size_t i = 0; i < 8; ++i) {
    EXPECT_EQ(results2["results"][i]["peak_load"], results["results"][i]["peak_load"]);
    EXPECT_EQ(results2["results"][i]["cached"], true);
  }
  auto metrics = c.Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_NE(metrics->body.find("rockcal_job_duration_seconds_count 8\n"), std::string::npos)
      << metrics->body;

  // The command-line client against the same server.
  std::string at = " --server " + server.url();
  auto [status_rc, status_out] = run_cli("status " + std::to_string(id) + at);
  EXPECT_EQ(status_rc, 0) << status_out;
  EXPECT_NE(status_out.find("succeeded"), std::string::npos) << status_out;
  EXPECT_NE(status_out.find("100%"), std::string::npos) << status_out;
  auto [csv_rc, csv_out] = run_cli("results " + std::to_string(id) + " --csv" + at);
  EXPECT_EQ(csv_rc, 0);
  EXPECT_EQ(csv_out, csv->body);
  auto [cancel_rc, cancel_out] = run_cli("cancel " + std::to_string(id) + at);
  EXPECT_EQ(cancel_rc, 1) << "a finished campaign cannot be cancelled";
  EXPECT_NE(cancel_out.find("409"), std::string::npos) << cancel_out;
  auto [list_rc, list_out] = run_cli("list" + at);
  EXPECT_EQ(list_rc, 0);
  EXPECT_NE(list_out.find("campaign " + std::to_string(id2)), std::string::npos) << list_out;

  EXPECT_EQ(server.terminate(), 0) << server.stderr_text();
}

TEST(Acceptance, CliSubmitsAndWaitsWithRanksZero) {
  TempDir dir;
  ServerProcess server(dir.path(), {"--engine", engine_binary(), "--ranks-per-job", "0"});
  server.start();
  auto file = dir.path() / "sweep.json";
  std::ofstream(file) << sweep_request({"btt"}, {40}, {45, 55}).dump();
  std::string at = " --server " + server.url();
  auto [submit_rc, submit_out] = run_cli("submit " + file.string() + at);
  ASSERT_EQ(submit_rc, 0) << submit_out;
  std::int64_t id = std::stoll(submit_out);
  auto [wait_rc, wait_out] = run_cli("status --wait " + std::to_string(id) + at);
  EXPECT_EQ(wait_rc, 0) << wait_out;
  EXPECT_NE(wait_out.find("2/2 done"), std::string::npos) << wait_out;
  auto [bad_rc, bad_out] = run_cli("submit " + (dir.path() / "missing.json").string() + at);
  EXPECT_NE(bad_rc, 0);
}

}  // namespace
}  // namespace rockcal::test
