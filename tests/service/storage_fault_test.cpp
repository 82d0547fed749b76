// Storage faults injected while the service runs, as SQLite's own suite injects them: a full
// database (a VFS shim whose writes fail with SQLITE_FULL), a write lock another connection holds
// (SQLITE_BUSY), and a job directory that cannot be created for a moment. The server answers a
// write it cannot store with the reason (507, 503), keeps serving reads, loses nothing stored,
// reports the fault on /healthz and /metrics, and once the fault clears stores the results it
// kept, ends the campaign and reports healthy again.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cstdlib>

#include "api_server_fixture.hpp"
#include "fault_vfs.hpp"

namespace rockcal::test {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

struct StorageFaults : ApiServerFixture {
  void SetUp() override {
    install_fault_vfs();
    setenv("FAKE_DEM_SLEEP", "1", 1);  // inherited by the fake engine: each run takes a second
  }
  void TearDown() override {
    set_write_fault(SQLITE_OK);
    ApiServerFixture::TearDown();
    unsetenv("FAKE_DEM_SLEEP");
  }

  std::int64_t submit(double fr0, std::vector<double> fs0) {
    auto r = client().Post("/api/v1/campaigns", sweep_request({"uct"}, {fr0}, fs0).dump(),
                           "application/json");
    EXPECT_TRUE(r && r->status == 201) << (r ? r->body : httplib::to_string(r.error()));
    return r ? json::parse(r->body)["id"].get<std::int64_t>() : 0;
  }
  std::string state_of(std::int64_t campaign) {
    auto c = client();
    return get_json(c, "/api/v1/campaigns/" + std::to_string(campaign))["state"];
  }
  std::int64_t faults(const std::string& kind) {
    const auto counts = service->store().health().counts();
    const auto it = counts.find(kind);
    return it == counts.end() ? 0 : it->second;
  }
};

TEST_F(StorageFaults, AFullDatabaseKeepsTheResultsUntilItCanStoreThem) {
  start();
  auto c = client();
  const std::int64_t stored = submit(50, {60});
  ASSERT_TRUE(poll_until([&] { return state_of(stored) == "succeeded"; }, 20s));
  const json stored_results = get_json(c, "/api/v1/campaigns/1/results");

  const std::int64_t id = submit(51, {61, 62});
  ASSERT_TRUE(poll_until([&] { return service->store().counts(id).running == 2; }, 10s));
  {
    WriteFault full(SQLITE_FULL);
    // Both runs end within about a second; their results cannot be stored and wait.
    ASSERT_TRUE(poll_until([&] { return faults("full") >= 4; }, 10s));
    EXPECT_EQ(service->store().counts(id).running, 2);
    // Reads are served, and what was stored before is all there.
    EXPECT_EQ(state_of(id), "running");
    EXPECT_EQ(get_json(c, "/api/v1/campaigns/1/results"), stored_results);
    // A write is answered with its reason.
    auto refused =
        c.Post("/api/v1/campaigns", sweep_request({"uct"}, {52}, {63}).dump(), "application/json");
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 507);
    EXPECT_EQ(json::parse(refused->body),
              json({{"error", "storage full: database or disk is full; nothing was stored"}}));
    auto health = c.Get("/healthz");
    ASSERT_TRUE(health);
    EXPECT_EQ(health->status, 503);
    const json h = json::parse(health->body);
    EXPECT_EQ(h["status"], "storage_fault");
    EXPECT_EQ(h["storage"]["kind"], "full");
    EXPECT_EQ(h["storage"]["error"], "database or disk is full");
    auto metrics = c.Get("/metrics");
    ASSERT_TRUE(metrics);
    EXPECT_EQ(metrics->body.find("rockcal_storage_faults_total{kind=\"full\"} 0\n"),
              std::string::npos);
    EXPECT_NE(metrics->body.find("rockcal_storage_faults_total{kind=\"full\"} "),
              std::string::npos);
  }
  // The fault has cleared: the kept results are stored, the campaign ends, health recovers.
  ASSERT_TRUE(poll_until([&] { return state_of(id) == "succeeded"; }, 10s));
  const json results = get_json(c, "/api/v1/campaigns/" + std::to_string(id) + "/results");
  ASSERT_EQ(results["results"].size(), 2u);
  for (const auto& row : results["results"]) EXPECT_EQ(row["peak_load"], 51.0) << row.dump();
  EXPECT_EQ(get_json(c, "/healthz")["status"], "ok");
  EXPECT_EQ(service->store().campaign_count(), 2);  // the refused request stored nothing
  EXPECT_EQ(service->store().counts().failed, 0);
  submit(52, {63});
}

TEST_F(StorageFaults, AHeldWriteLockIsAnswered503AndTheResultIsStoredAfter) {
  start(std::nullopt, 100, {}, [](orch::ServiceConfig& s) { s.busy_timeout_ms = 200; });
  auto c = client();
  const std::int64_t id = submit(51, {61});
  ASSERT_TRUE(poll_until([&] { return service->store().counts(id).running == 1; }, 10s));
  sqlite3* holder = nullptr;
  ASSERT_EQ(sqlite3_open((dir.path() / "api.db").c_str(), &holder), SQLITE_OK);
  // The service may be writing at this moment (a progress update): wait for it, then hold.
  sqlite3_busy_timeout(holder, 5000);
  ASSERT_EQ(sqlite3_exec(holder, "BEGIN IMMEDIATE", nullptr, nullptr, nullptr), SQLITE_OK);
  // The run ends; its result meets the lock and waits.
  ASSERT_TRUE(poll_until([&] { return faults("busy") >= 2; }, 10s));
  auto refused =
      c.Post("/api/v1/campaigns", sweep_request({"uct"}, {52}, {63}).dump(), "application/json");
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 503);
  EXPECT_EQ(refused->get_header_value("Retry-After"), "1");
  EXPECT_EQ(json::parse(refused->body),
            json({{"error", "storage busy: database is locked; retry shortly"}}));
  EXPECT_EQ(get_json(c, "/api/v1/campaigns")["total"], 1);  // reads are served
  auto health = c.Get("/healthz");
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, 503);
  EXPECT_EQ(json::parse(health->body)["storage"]["kind"], "busy");
  EXPECT_EQ(service->store().counts(id).running, 1);

  sqlite3_exec(holder, "ROLLBACK", nullptr, nullptr, nullptr);
  sqlite3_close(holder);
  ASSERT_TRUE(poll_until([&] { return state_of(id) == "succeeded"; }, 10s));
  EXPECT_EQ(get_json(c, "/healthz")["status"], "ok");
  submit(52, {63});
}

TEST_F(StorageFaults, AJobDirectoryThatCannotBeMadeForAMomentIsTriedAgain) {
  start();
  const auto jobs = service->jobs_dir();
  const auto away = jobs.string() + ".away";
  std::filesystem::rename(jobs, away);
  std::ofstream(jobs) << "not a directory\n";  // job directories cannot be created below it
  const std::int64_t id = submit(53, {64});
  ASSERT_TRUE(poll_until([&] { return service->store().counts(id).running == 1; }, 10s));
  std::this_thread::sleep_for(400ms);
  std::filesystem::remove(jobs);
  std::filesystem::rename(away, jobs);
  ASSERT_TRUE(poll_until([&] { return state_of(id) == "succeeded"; }, 10s));
  const auto job = service->store().job(1);
  ASSERT_TRUE(job);
  EXPECT_EQ(job->attempts, 1);  // the passing fault cost no attempt
}

}  // namespace
}  // namespace rockcal::test
