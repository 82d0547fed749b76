// The orchestrator with the fault-injecting fake engine: retries, failures kept with their log,
// timeouts, cancellation, the submit-and-wait API, and the one job runner on the pool
// (orch::PoolRunner) that calibration, diagnosis and twins run their jobs through.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <thread>

#include "orchestrator/all_kinds.hpp"
#include "orchestrator/job_service.hpp"
#include "orchestrator/local_executor.hpp"
#include "orchestrator/pool_runner.hpp"
#include "orchestrator/process_groups.hpp"
#include "support.hpp"

namespace rockcal::orch {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;

struct JobServiceTest : ::testing::Test {
  test::TempDir dir;
  std::unique_ptr<JobService> service;

  void start(int workers, std::chrono::milliseconds timeout = 60s, int attempts = 3) {
    ServiceConfig cfg;
    cfg.db_path = dir.path() / "svc.db";
    cfg.workers = workers;
    cfg.max_attempts = attempts;
    cfg.job_timeout = timeout;
    LocalExecutorConfig exec;
    exec.engine = test::fake_engine();
    exec.ranks = 0;
    exec.grace = 1s;
    service = std::make_unique<JobService>(cfg, std::make_unique<LocalExecutor>(exec));
    add_all_kinds(service->kinds());
    service->start();
  }
  void TearDown() override {
    if (service) service->stop();
    EXPECT_TRUE(test::processes_mentioning(dir.path().string()).empty()) << "jobs left running";
  }

  json points_request(std::vector<std::pair<double, double>> points) {
    json r = test::sweep_request({"uct"}, {1}, {1});
    r.erase("grid");
    r["points"] = json::array();
    for (auto [a, b] : points) r["points"].push_back({a, b});
    return r;
  }
  bool finished(std::int64_t campaign) {
    auto c = service->store().counts(campaign);
    return c.queued + c.running == 0;
  }
  db::JobRow job_with_fr0(std::int64_t campaign, double fr0) {
    for (const auto& row : service->store().campaign_results(campaign)) {
      if (row.job.fr0 == fr0) return row.job;
    }
    throw std::runtime_error("no such job");
  }
  // A UCT of the tiny template at (fr0, 60) on the packing `seed` (the fake engine's peak load is
  // fr0 + seed - 1; fr0 61 ends without a peak, 17 hangs).
  static json uct_job(double fr0, std::uint64_t seed) {
    json spec = test::tiny_job_template();
    spec["test"] = "uct";
    spec["bond"] = {{"fr0", fr0}, {"fs0", 60.0}};
    spec["sample"]["seed"] = seed;
    return spec;
  }
  // Waits until the campaign's job at fr0 runs, then calls `then` (on its own thread).
  std::thread when_running(std::int64_t campaign, double fr0, std::function<void()> then) {
    return std::thread([this, campaign, fr0, then] {
      test::poll_until(
          [&] {
            for (const auto& row : service->store().campaign_results(campaign))
              if (row.job.fr0 == fr0 && row.job.state == "running") return true;
            return false;
          },
          10s);
      then();
    });
  }
};

TEST_F(JobServiceTest, FailuresAreRetriedKeptWithTheirLogAndDoNotStopTheCampaign) {
  start(2);
  // 13 crashes always, 19 fails once, 23 is an invalid spec, 31 and 37 are healthy.
  auto id = service->create_campaign(points_request({{13, 1}, {19, 1}, {23, 1}, {31, 1}, {37, 1}}));
  ASSERT_TRUE(test::poll_until([&] { return finished(id); }, 60s));
  auto crash = job_with_fr0(id, 13);
  EXPECT_EQ(crash.state, "failed");
  EXPECT_EQ(crash.attempts, 3);
  ASSERT_TRUE(crash.error);
  EXPECT_NE(crash.error->find("signal 11"), std::string::npos) << *crash.error;
  EXPECT_NE(crash.error->find("fake-rockcal-dem: crashing"), std::string::npos) << *crash.error;
  auto flaky = job_with_fr0(id, 19);
  EXPECT_EQ(flaky.state, "succeeded");
  EXPECT_EQ(flaky.attempts, 2);
  auto invalid = job_with_fr0(id, 23);
  EXPECT_EQ(invalid.state, "failed");
  EXPECT_EQ(invalid.attempts, 1) << "an invalid spec is not retried";
  EXPECT_EQ(job_with_fr0(id, 31).state, "succeeded");
  EXPECT_EQ(job_with_fr0(id, 37).state, "succeeded");
  auto results = service->store().campaign_results(id);
  int with_result = 0;
  for (const auto& r : results) with_result += r.result ? 1 : 0;
  EXPECT_EQ(with_result, 3);
}

TEST_F(JobServiceTest, HangingJobsTimeOutAndAreStopped) {
  start(1, 700ms, 2);
  auto id = service->create_campaign(points_request({{17, 1}, {31, 1}}));
  ASSERT_TRUE(test::poll_until([&] { return finished(id); }, 30s));
  auto hung = job_with_fr0(id, 17);
  EXPECT_EQ(hung.state, "failed");
  EXPECT_EQ(hung.attempts, 2);
  EXPECT_NE(hung.error.value_or("").find("timed out"), std::string::npos);
  EXPECT_EQ(job_with_fr0(id, 31).state, "succeeded");
}

TEST_F(JobServiceTest, CancelStopsRunningJobsAndDropsQueuedOnes) {
  start(1);
  auto id = service->create_campaign(points_request({{17, 1}, {31, 1}, {37, 1}}));
  ASSERT_TRUE(test::poll_until(
      [&] {
        auto j = job_with_fr0(id, 17);
        return j.state == "running" && j.handle;
      },
      10s));
  pid_t pgid = std::stoi(*job_with_fr0(id, 17).handle);
  EXPECT_EQ(service->cancel_campaign(id), db::CancelOutcome::cancelled);
  auto counts = service->store().counts(id);
  EXPECT_EQ(counts.cancelled, 3);
  EXPECT_TRUE(test::poll_until([&] { return group_members(pgid).empty(); }, 10s));
  EXPECT_EQ(service->cancel_campaign(id), db::CancelOutcome::already_finished);
}

// A diagnosis runs thousands of jobs of 10-100 ms: the pool must notice a short job's end soon,
// not a whole poll interval (100 ms) later. Measured from the moment the fake engine wrote its
// result (its "ended_at") to the job's finished_at, so a loaded machine's slow process start-up
// does not count (it runs alone: RUN_SERIAL); the exit, the result read and the commit take
// 30-40 ms, polling every 100 ms would add about 50 ms more.
TEST_F(JobServiceTest, AloneAShortJobIsRecordedSoonAfterItEnds) {
  // The pool looks at a job 1 ms after its launch and then at intervals growing by 1.5x (up to
  // poll_interval), so a job is noticed within about half its own run time, plus the engine's exit
  // after it wrote its result. Measured against each job's run time, so that a loaded machine
  // (slower jobs) does not fail it; a pool that looked once a second would.
  start(1);
  auto id = service->create_campaign(
      points_request({{31, 1}, {37, 1}, {41, 1}, {43, 1}, {47, 1}, {53, 1}, {59, 1}}));
  ASSERT_TRUE(test::poll_until([&] { return finished(id); }, 60s));
  std::vector<double> excess_s;
  for (const auto& row : service->store().campaign_results(id)) {
    ASSERT_EQ(row.job.state, "succeeded");
    ASSERT_TRUE(row.result);
    ASSERT_TRUE(row.job.started_at && row.job.finished_at);
    double ended = json::parse(row.result->result).at("ended_at").get<double>();
    double run_s = ended - *row.job.started_at;
    excess_s.push_back((*row.job.finished_at - ended) - 0.5 * run_s);
  }
  std::sort(excess_s.begin(), excess_s.end());
  EXPECT_LT(excess_s[excess_s.size() / 2], 0.03)
      << "median over " << excess_s.size() << " jobs of (noticed after end - half the run time)";
}

TEST_F(JobServiceTest, DriversSubmitJobsAndWaitForResults) {
  // A stand-in for the calibration kind: evaluates two points, then a cached one, and reports.
  CampaignKind kind;
  kind.name = "probe";
  kind.plan = [](const json&, const Limits&) { return CampaignPlan{"probe", {}}; };
  kind.driver = [](DriverContext& ctx) {
    PoolRunner runner(ctx.service, ctx.campaign_id, ctx.stop);
    json summary = json::array();
    for (double fr0 : {41.0, 43.0, 41.0}) {
      const Realisation run = runner.run({uct_job(fr0, 1)}).value().front();
      summary.push_back(
          {{"state", run.state}, {"cached", run.cached}, {"peak", run.peak_load_n.value_or(-1)}});
    }
    return summary;
  };
  ServiceConfig cfg;
  start(2);
  service->kinds().add(kind);
  auto id = service->create_campaign({{"kind", "probe"}});
  ASSERT_TRUE(test::poll_until(
      [&] {
        return service->store().campaign(id)->driver_status == std::optional<std::string>("done");
      },
      30s));
  json summary = json::parse(*service->store().campaign(id)->summary);
  ASSERT_EQ(summary.size(), 3u);
  EXPECT_EQ(summary[0]["state"], "succeeded");
  EXPECT_EQ(summary[0]["peak"], 41.0);  // the fake engine reports fr0 as the peak
  EXPECT_EQ(summary[1]["peak"], 43.0);
  EXPECT_EQ(summary[2]["cached"], true) << "a point already computed is not run again";
  EXPECT_EQ(service->store().counts(id).total(), 3);
}

TEST_F(JobServiceTest, WaitingDriverSeesCancellation) {
  start(1);
  auto id = service->create_campaign(points_request({{31, 1}}));
  json spec = test::tiny_job_template();
  spec["test"] = "uct";
  spec["bond"]["fr0"] = 17;  // hangs
  auto job = service->submit_job(id, spec);
  std::thread canceller([&] {
    test::poll_until([&] { return service->store().job_state(job) == "running"; }, 10s);
    service->cancel_campaign(id);
  });
  auto outcome = service->wait_job(job);
  canceller.join();
  EXPECT_EQ(outcome.state, "cancelled");
  EXPECT_FALSE(outcome.result);
}

// The one runner: one realisation per job in order, with its values, seed and result.json; a
// failure's reason, and a run without a peak as a failed run with the engine's reason; equal jobs
// within a batch run once; a job run before answered by the cache and said so (a restarted
// campaign's replay).
TEST_F(JobServiceTest, PoolRunnerGivesEachJobItsRealisationAndRunsEqualJobsOnce) {
  start(2);
  const auto campaign = service->create_campaign(points_request({{1, 1}}));
  PoolRunner runner(*service, campaign, {});
  const auto runs = runner.run({uct_job(41, 1), uct_job(41, 2), uct_job(61, 1), uct_job(41, 1)});
  ASSERT_TRUE(runs);
  ASSERT_EQ(runs->size(), 4u);
  const Realisation& first = (*runs)[0];
  EXPECT_EQ(first.state, "succeeded");
  EXPECT_EQ(first.seed, 1u);
  EXPECT_EQ(first.peak_load_n, 41.0);
  EXPECT_EQ(first.strength_pa, 60.0);
  EXPECT_EQ(first.youngs_modulus_pa, 1000.0);
  EXPECT_EQ(first.error, "");
  EXPECT_FALSE(first.cached);
  EXPECT_EQ(first.result.value("engine_version", ""), "fake");
  EXPECT_EQ((*runs)[1].seed, 2u);
  EXPECT_EQ((*runs)[1].peak_load_n, 42.0);
  const Realisation& no_peak = (*runs)[2];
  EXPECT_EQ(no_peak.state, "failed");
  EXPECT_EQ(no_peak.error, "no peak: the load fell on a loose particle with no bond broken (fake)");
  EXPECT_FALSE(no_peak.peak_load_n);
  EXPECT_TRUE(no_peak.result.is_null());
  EXPECT_EQ((*runs)[3].job_id, first.job_id);
  EXPECT_EQ(service->store().counts(campaign).total(), 1 + 3);

  const auto again = runner.run({uct_job(41, 1)});
  ASSERT_TRUE(again);
  EXPECT_TRUE(again->front().cached);
  EXPECT_NE(again->front().job_id, first.job_id);
  EXPECT_EQ(again->front().peak_load_n, 41.0);
}

// A cancelled campaign, or a stop (the server shutting down), ends the batch with no partial
// results.
TEST_F(JobServiceTest, PoolRunnerEndsWithoutResultsWhenTheCampaignIsCancelled) {
  start(2);
  const auto campaign = service->create_campaign(points_request({{1, 1}}));
  PoolRunner runner(*service, campaign, {});
  std::thread canceller = when_running(campaign, 17, [&] { service->cancel_campaign(campaign); });
  const auto runs = runner.run({uct_job(41, 1), uct_job(17, 1)});
  canceller.join();
  EXPECT_FALSE(runs);
}

TEST_F(JobServiceTest, PoolRunnerEndsWithoutResultsOnAStop) {
  start(2);
  const auto campaign = service->create_campaign(points_request({{1, 1}}));
  std::stop_source stop;
  PoolRunner runner(*service, campaign, stop.get_token());
  std::thread stopper = when_running(campaign, 17, [&] { stop.request_stop(); });
  const auto runs = runner.run({uct_job(17, 1)});
  stopper.join();
  EXPECT_FALSE(runs);
}

}  // namespace
}  // namespace rockcal::orch
