// The calibration kind inside the real service (JobService, SQLite store, local executor), with a
// formula engine: the campaign runs to a feasible report (which `rockcal status` shows as a table),
// bad campaigns are refused naming the field, a running one shows its budget and pace, and a
// server stopped mid-calibration resumes without re-running finished evaluations.
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <thread>

#include "api/cli/calibration_text.hpp"
#include "api/cli/status_text.hpp"
#include "orchestrator/all_kinds.hpp"
#include "orchestrator/job_service.hpp"
#include "orchestrator/local_executor.hpp"
#include "orchestrator/request_error.hpp"
#include "synthetic.hpp"
#include "tests/service/fault_vfs.hpp"

namespace rockcal::calibration {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;

class ServiceCalibration : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("rockcal-cal-svc-" + std::to_string(getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    setenv("FAKE_DEM_RUNS", runs_file().c_str(), 1);
  }
  void TearDown() override {
    if (service_) service_->stop();
    service_.reset();
    unsetenv("FAKE_DEM_NO_PEAK_SEEDS");
    std::filesystem::remove_all(dir_);
  }

  // `configure` may change the service's settings (e.g. how long a driver waits out a fault).
  void start(const std::function<void(orch::ServiceConfig&)>& configure = {}) {
    orch::ServiceConfig cfg;
    cfg.db_path = dir_ / "svc.db";
    cfg.workers = 2;
    if (configure) configure(cfg);
    orch::LocalExecutorConfig exec;
    exec.engine = FAKE_DEM;
    exec.ranks = 0;
    service_ = std::make_unique<orch::JobService>(cfg, std::make_unique<orch::LocalExecutor>(exec));
    orch::add_all_kinds(service_->kinds());
    service_->start();
  }

  std::optional<std::string> driver_status(std::int64_t id) {
    return service_->store().campaign(id)->driver_status;
  }

  bool wait_for(const std::function<bool()>& condition, std::chrono::seconds timeout) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
      if (condition()) return true;
      std::this_thread::sleep_for(20ms);
    }
    return condition();
  }

  // Every job of the campaign, for a failure message: what a stuck driver is waiting for.
  std::string job_table(std::int64_t id) {
    std::string out = "driver " + driver_status(id).value_or("(none)") + "; jobs:\n";
    service_->store().with_connection([&](db::Connection& conn) {
      auto st = conn.prepare(
          "SELECT id, state, cached, attempts, substr(hash, 1, 8), coalesce(error, '') || ' h=' || "
          "coalesce(handle, '-') FROM jobs "
          "WHERE campaign_id = ? ORDER BY id");
      st.bind_all(id);
      while (st.step()) {
        out += std::to_string(st.int64(0)) + " " + st.text(1) +
               " cached=" + std::to_string(st.int64(2)) +
               " attempts=" + std::to_string(st.int64(3)) + " " + st.text(4) + " " + st.text(5) +
               "\n";
      }
    });
    return out;
  }

  std::string runs_file() const { return (dir_ / "runs.txt").string(); }
  std::vector<std::string> runs() const {
    std::vector<std::string> lines;
    std::ifstream in(runs_file());
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }

  static json request() {
    return testing::campaign_json(testing::power_law({40, 90}), {{"name", "service twin"}});
  }
  // Each evaluation an ensemble of `n` packings (random: the seed makes another specimen).
  static json ensemble_request(int n) {
    json r = request();
    r["job"]["sample"]["packing"] = "random";
    r["realisations"] = n;
    return r;
  }

  std::filesystem::path dir_;
  std::unique_ptr<orch::JobService> service_;
};

TEST_F(ServiceCalibration, RunsToAFeasibleReport) {
  start();
  const std::int64_t id = service_->create_campaign(request());
  ASSERT_TRUE(wait_for([&] { return driver_status(id) == "done"; }, 60s));
  const json report = json::parse(*service_->store().campaign(id)->summary);
  EXPECT_EQ(report["verdict"], "feasible") << report["verdict_reason"];
  EXPECT_NEAR(report["best"]["fr0"].get<double>() / 40, 1.0, 0.1);
  EXPECT_NEAR(report["best"]["fs0"].get<double>() / 90, 1.0, 0.1);
  EXPECT_LE(report["evaluations"].get<int>(), 40);
  // Every evaluation is two ordinary jobs of the campaign, each run once.
  EXPECT_EQ(service_->store().counts(id).total(), 2 * report["evaluations"].get<int>());
  EXPECT_EQ(int(runs().size()), 2 * report["evaluations"].get<int>());
  // Every evaluation ran jobs (none came from the cache), so all of them set the pace.
  EXPECT_EQ(report["pace"]["evaluations_timed"], report["evaluations"]);
  EXPECT_GT(report["pace"]["wall_seconds"].get<double>(), 0.0);
  // `rockcal status` shows this report as a table, not as its JSON.
  const std::string text = api::calibration_text(report);
  EXPECT_EQ(
      text.substr(0, text.find('\n')),
      "verdict: feasible - both peak loads within 2% of their targets; the strengths are unique");
  EXPECT_NE(text.find("\n  UCT "), std::string::npos) << text;
  EXPECT_NE(text.find("\n  BTT "), std::string::npos) << text;
  EXPECT_NE(text.find("\nevaluations: " + report["evaluations"].dump() +
                      " of 64 (search 40, valley trace 24), stopped: "),
            std::string::npos)
      << text;
}

// E and nu as targets through the service's pool: the stiffness stage's elastic runs are jobs of
// the campaign, the report states the stage, and every UCT and BTT job of the strength search ran
// at the stiffnesses it reports (the fake packing: E = 0.4 K_r, nu = eq. 3's nu + 0.05).
TEST_F(ServiceCalibration, EAndNuTargetsRunTheStrengthSearchAtTheStagesStiffnesses) {
  start();
  json r = request();
  r["targets"]["youngs_modulus"] = 5000;
  r["targets"]["poisson_ratio"] = 0.25;
  const std::int64_t id = service_->create_campaign(r);
  ASSERT_TRUE(wait_for([&] { return driver_status(id) == "done"; }, 60s)) << job_table(id);
  const json report = json::parse(*service_->store().campaign(id)->summary);
  const json& s = report["stiffness"];
  ASSERT_TRUE(s.is_object()) << report.dump();
  EXPECT_EQ(s["met"], true) << s.dump();
  EXPECT_NEAR(s["kr"].get<double>(), 5000 / 0.4, 1e-6 * 12500);
  EXPECT_NEAR(s["nu_input"].get<double>(), 0.2, 0.03);  // nu within 0.03 of its target
  EXPECT_EQ(report["verdict"], "feasible") << report["verdict_reason"];
  int elastic = 0, strength = 0;
  service_->store().with_connection([&](db::Connection& conn) {
    auto st = conn.prepare("SELECT spec FROM jobs WHERE campaign_id = ? ORDER BY id");
    st.bind_all(id);
    while (st.step()) {
      const json job = json::parse(st.text(0));
      if (job["test"] == "elastic") {
        ++elastic;
        continue;
      }
      ++strength;
      EXPECT_EQ(job["material"]["kr"], s["kr"]);
      EXPECT_EQ(job["material"]["nu"], s["nu_input"]);
    }
  });
  std::size_t packings = 0;  // every packing of every elastic run is one job
  for (const json& run : s["runs"]) packings += run["job_ids"].size();
  EXPECT_EQ(elastic, int(packings));
  EXPECT_EQ(strength, 2 * report["evaluations"].get<int>());
}

TEST_F(ServiceCalibration, BadCampaignIsRefusedNamingTheField) {
  start();
  json bad = request();
  bad["bounds"]["fr0"] = {100, 10};
  try {
    service_->create_campaign(bad);
    FAIL() << "accepted inverted bounds";
  } catch (const orch::RequestError& e) {
    EXPECT_EQ(e.field, "bounds.fr0");
  }
}

TEST_F(ServiceCalibration, StoppedServerResumesWithoutRerunningFinishedEvaluations) {
  // The 2-D search takes ~20 evaluations here; stop the server after the first 8.
  json r = request();
  r["strategy"] = "direct_2d";
  start();
  const std::int64_t id = service_->create_campaign(r);
  ASSERT_TRUE(wait_for([&] { return service_->store().counts(id).succeeded >= 16; }, 60s))
      << job_table(id);
  // While it runs, the summary shows the history so far.
  const json progress = json::parse(service_->store().campaign(id)->summary.value_or("null"));
  ASSERT_TRUE(progress.is_object());
  EXPECT_TRUE(progress["stop_reason"].is_null());
  EXPECT_GE(progress["history"].size(), 6u);
  // ... and what a client's progress line needs: the budget, and the pace once evaluations ran.
  EXPECT_EQ(progress["max_evaluations"], 40);
  EXPECT_EQ(progress["scatter_runs"], 0);
  EXPECT_GT(progress["pace"]["seconds_per_evaluation"].get<double>(), 0.0);
  EXPECT_EQ(progress["progress"]["done"], progress["evaluations"]);
  EXPECT_EQ(progress["progress"]["budget"], 64);
  const json campaign = {{"id", id},
                         {"kind", "calibration"},
                         {"state", "running"},
                         {"progress", {{"running", 2}}},
                         {"summary", progress}};
  const std::string line = api::progress_line(campaign);
  EXPECT_EQ(
      line.rfind("campaign " + std::to_string(id) + " running: " + progress["evaluations"].dump() +
                     " of 64 evaluations done (search 40, valley trace 24), best misfit ",
                 0),
      0u)
      << line;
  EXPECT_NE(line.find(", ETA "), std::string::npos) << line;
  EXPECT_EQ(line.find("ETA 0s"), std::string::npos) << line;
  service_->stop();  // a shutdown: the driver stays "running" and resumes at the next start
  service_.reset();
  const std::size_t before = runs().size();
  start();
  ASSERT_TRUE(wait_for([&] { return driver_status(id) == "done"; }, 60s)) << job_table(id);
  const json report = json::parse(*service_->store().campaign(id)->summary);
  EXPECT_EQ(report["verdict"], "feasible");
  // No finished (test, point) ran twice; only jobs cut short by the stop may have run again.
  std::map<std::string, int> times;
  for (const std::string& line : runs()) ++times[line];
  int repeated = 0;
  for (const auto& [line, n] : times) repeated += n - 1;
  EXPECT_LE(repeated, 2) << "more re-runs than jobs that can be running at a stop (2 workers)";
  EXPECT_GT(runs().size(), before);
  EXPECT_EQ(int(times.size()), 2 * report["evaluations"].get<int>());
  std::printf("resumed calibration: %d evaluations, %zu engine runs before the stop, %d re-run\n",
              report["evaluations"].get<int>(), before, repeated);
}

// A disk that fills mid-campaign and is freed again. The server is stopped halfway and started
// again on the full disk, so the resumed driver's first store write (its progress) meets the
// fault: its writes wait and retry, the campaign stays running, nothing stored is lost, and once
// the disk takes writes again it ends with its report.
TEST_F(ServiceCalibration, ADiskFullMidCampaignIsWaitedOutAndTheCampaignEnds) {
  test::install_fault_vfs();  // before the store opens its connections
  start();
  const std::int64_t id = service_->create_campaign(request());
  ASSERT_TRUE(wait_for([&] { return service_->store().counts(id).succeeded >= 4; }, 30s))
      << job_table(id);
  service_->stop();
  std::map<std::int64_t, std::optional<double>> stored;  // job id -> peak load
  for (const db::JobResultRow& row : service_->store().campaign_results(id)) {
    if (row.job.state == db::kSucceeded) stored[row.job.id] = row.result->peak_load;
  }
  auto full_faults = [&] {
    const auto counts = service_->store().health().counts();
    return counts.contains("full") ? counts.at("full") : 0;
  };
  auto stored_now = [&] {
    std::map<std::int64_t, std::optional<double>> now;
    for (const db::JobResultRow& row : service_->store().campaign_results(id)) {
      if (stored.contains(row.job.id) && row.result) now[row.job.id] = row.result->peak_load;
    }
    return now;
  };
  {
    test::WriteFault full(SQLITE_FULL);
    service_->start();
    ASSERT_TRUE(wait_for([&] { return full_faults() >= 6; }, 20s));
    EXPECT_EQ(driver_status(id), "running");
    EXPECT_EQ(stored_now(), stored);
  }
  ASSERT_TRUE(wait_for([&] { return driver_status(id) == "done"; }, 60s)) << job_table(id);
  const json report = json::parse(*service_->store().campaign(id)->summary);
  EXPECT_EQ(report["verdict"], "feasible") << report["verdict_reason"];
  EXPECT_EQ(stored_now(), stored);
  EXPECT_EQ(service_->store().counts(id).failed, 0) << job_table(id);
  std::printf(
      "disk full mid-campaign: %zu jobs stored before it, %lld writes refused, %d evaluations\n",
      stored.size(), static_cast<long long>(full_faults()), report["evaluations"].get<int>());
}

// A driver waits out a storage fault for a bounded time only: past driver_storage_retry's
// give_up_after its campaign fails, with the store's reason, once the end can be stored.
TEST_F(ServiceCalibration, ADiskFullLongerThanTheDriverWaitsFailsTheCampaignWithTheReason) {
  test::install_fault_vfs();
  start([](orch::ServiceConfig& c) { c.driver_storage_retry.give_up_after = 200ms; });
  service_->stop();  // the campaign is stored now, its driver starts with the service
  const std::int64_t id = service_->create_campaign(request());
  {
    test::WriteFault full(SQLITE_FULL);
    service_->start();
    // The driver has given up on its progress; its end waits for the disk.
    std::this_thread::sleep_for(1s);
    EXPECT_EQ(driver_status(id), "running");
  }
  ASSERT_TRUE(wait_for([&] { return driver_status(id) == "failed"; }, 10s)) << job_table(id);
  EXPECT_EQ(json::parse(*service_->store().campaign(id)->summary),
            json({{"error",
                   "step 'UPDATE campaigns SET driver_status = ?, summary = COALESCE(?, summary) "
                   "WHERE id = ?': database or disk is full"}}));
}

// The formula engine multiplies its loads by 1 + (s - 1) / 100 on seed s, so an ensemble of seeds
// 1-3 has mean 1.01 x the power law and standard deviation 0.01 x it, exactly.
TEST_F(ServiceCalibration, EvaluationsAreEnsemblesMatchedByTheirMean) {
  start();
  const std::int64_t id = service_->create_campaign(ensemble_request(3));
  ASSERT_TRUE(wait_for([&] { return driver_status(id) == "done"; }, 90s)) << job_table(id);
  const json report = json::parse(*service_->store().campaign(id)->summary);
  EXPECT_EQ(report["verdict"], "feasible") << report["verdict_reason"];
  EXPECT_EQ(report["realisations"], 3);
  const int evaluations = report["evaluations"].get<int>();
  EXPECT_EQ(service_->store().counts(id).total(), 6 * evaluations);
  EXPECT_EQ(int(runs().size()), 6 * evaluations) << "every realisation run once";
  const json& best = report["best"];
  const PeakLoads p = testing::power_law({best["fr0"].get<double>(), best["fs0"].get<double>()});
  for (const auto& [test, load] : {std::pair("uct", p.uct_n), std::pair("btt", p.btt_n)}) {
    EXPECT_NEAR(best[test]["peak_load"].get<double>() / (1.01 * load), 1.0, 1e-12) << test;
    EXPECT_NEAR(best[test]["se"].get<double>() / (0.01 * load / std::sqrt(3.0)), 1.0, 1e-9) << test;
    EXPECT_EQ(best[test]["n"], 3);
    const json& runs = best["ensemble"][test]["realisations"];
    ASSERT_EQ(runs.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(runs[k]["seed"], k + 1);
      EXPECT_NEAR(runs[k]["peak_load_n"].get<double>() / ((1 + 0.01 * double(k)) * load), 1.0,
                  1e-12);
    }
  }
  // Each evaluation of the history carries its own mean, se and n.
  for (const json& e : report["history"]) {
    EXPECT_EQ(e["ensemble"]["uct"]["peak_load"]["n"], 3);
    EXPECT_EQ(e["ensemble"]["btt"]["peak_load"]["mean"], e["btt"]);
  }
}

// Seed 2 ends without a peak on every point: its runs are failed jobs, run once (not retried),
// listed with their reason, and the evaluation uses the mean of seeds 1 and 3.
TEST_F(ServiceCalibration, RunsWithoutAPeakAreLeftOutOfTheEnsembleAndCounted) {
  setenv("FAKE_DEM_NO_PEAK_SEEDS", "2", 1);
  start();
  const std::int64_t id = service_->create_campaign(ensemble_request(3));
  ASSERT_TRUE(wait_for([&] { return driver_status(id) == "done"; }, 90s)) << job_table(id);
  const json report = json::parse(*service_->store().campaign(id)->summary);
  EXPECT_EQ(report["verdict"], "feasible") << report["verdict_reason"];
  const int evaluations = report["evaluations"].get<int>();
  EXPECT_EQ(service_->store().counts(id).failed, 2 * evaluations);
  EXPECT_EQ(int(runs().size()), 6 * evaluations) << "a run without a peak is not retried";
  const json& best = report["best"];
  const PeakLoads p = testing::power_law({best["fr0"].get<double>(), best["fs0"].get<double>()});
  for (const auto& [test, load] : {std::pair("uct", p.uct_n), std::pair("btt", p.btt_n)}) {
    EXPECT_NEAR(best[test]["peak_load"].get<double>() / (1.01 * load), 1.0, 1e-12) << test;
    EXPECT_NEAR(best[test]["se"].get<double>() / (0.01 * load), 1.0, 1e-9) << test;
    EXPECT_EQ(best[test]["n"], 2);
    const json& ensemble = best["ensemble"][test];
    EXPECT_EQ(ensemble["failed"], 1);
    EXPECT_EQ(ensemble["realisations"][1]["state"], "failed");
    EXPECT_EQ(ensemble["realisations"][1]["peak_load_n"], nullptr);
    EXPECT_EQ(ensemble["realisations"][1]["error"],
              "no peak: no bond broke before the load fell (fake, seed 2)");
  }
}

}  // namespace
}  // namespace rockcal::calibration
