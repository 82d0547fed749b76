// The store on its own: migrations, atomic claims, result + success in one transaction, retries,
// the cache, cancellation outcomes.
#include <gtest/gtest.h>

#include <atomic>
#include <set>
#include <thread>

#include "db/migrations.hpp"
#include "db/store.hpp"
#include "support.hpp"

namespace rockcal::db {
namespace {

NewJob job(const std::string& hash, double fr0 = 1, double fs0 = 2) {
  return {"uct", fr0, fs0, "{}", hash};
}

ResultRow result_for(const JobRow& j, double peak) {
  ResultRow r;
  r.hash = j.hash;
  r.job_id = j.id;
  r.test = j.test;
  r.fr0 = j.fr0;
  r.fs0 = j.fs0;
  r.peak_load = peak;
  r.engine_version = "v";
  r.result = "{}";
  r.curve = "step\n1\n";
  return r;
}

struct StoreTest : ::testing::Test {
  test::TempDir dir;
  Store store{(dir.path() / "s.db").string()};
};

TEST_F(StoreTest, MigrationsAreRecordedAndIdempotent) {
  int latest = migrations().back().version;
  store.with_connection([&](Connection& c) {
    EXPECT_EQ(migrate(c), latest);
    auto st = c.prepare("SELECT COUNT(*), MAX(version) FROM schema_version");
    ASSERT_TRUE(st.step());
    EXPECT_EQ(st.int64(0), latest);
    EXPECT_EQ(st.int64(1), latest);
    auto fk = c.prepare("PRAGMA foreign_keys");
    ASSERT_TRUE(fk.step());
    EXPECT_EQ(fk.int64(0), 1);
    auto wal = c.prepare("PRAGMA journal_mode");
    ASSERT_TRUE(wal.step());
    EXPECT_EQ(wal.text(0), "wal");
  });
  Store again((dir.path() / "s.db").string());  // reopening applies nothing twice
  EXPECT_EQ(again.campaign_count(), 0);
}

TEST_F(StoreTest, ConcurrentClaimsNeverHandOutAJobTwice) {
  std::vector<NewJob> jobs;
  for (int i = 0; i < 200; ++i) jobs.push_back(job(std::to_string(i)));
  store.create_campaign("sweep", "c", "{}", false, jobs);
  std::mutex m;
  std::multiset<std::int64_t> claimed;
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t) {
    threads.emplace_back([&] {
      while (auto j = store.claim_job("local")) {
        std::lock_guard lock(m);
        claimed.insert(j->id);
      }
    });
  }
  for (auto& t : threads) t.join();
  EXPECT_EQ(claimed.size(), 200u);
  EXPECT_EQ(std::set<std::int64_t>(claimed.begin(), claimed.end()).size(), 200u);
  EXPECT_EQ(store.counts().running, 200);
}

TEST_F(StoreTest, SuccessStoresOneResultAndAnswersTwins) {
  // Two campaigns ask for the same point; only one run is needed.
  auto c1 = store.create_campaign("sweep", "a", "{}", false, {job("same")});
  auto c2 = store.create_campaign("sweep", "b", "{}", false, {job("same")});
  auto first = store.claim_job("local");
  ASSERT_TRUE(first);
  EXPECT_FALSE(store.claim_job("local")) << "an identical job must wait for its running twin";
  ASSERT_TRUE(store.finish_success(first->id, result_for(*first, 42)));
  EXPECT_EQ(store.counts(c1).succeeded, 1);
  auto c2_counts = store.counts(c2);
  EXPECT_EQ(c2_counts.succeeded, 1);
  EXPECT_EQ(c2_counts.cached, 1);
  auto rows = store.campaign_results(c2);
  ASSERT_EQ(rows.size(), 1u);
  ASSERT_TRUE(rows[0].result);
  EXPECT_EQ(rows[0].result->peak_load, 42);
  EXPECT_FALSE(rows[0].result->curve) << "listings leave the curve out";
  EXPECT_EQ(store.result("same")->curve, "step\n1\n");

  // A later campaign is answered at creation, without a queued job.
  auto c3 = store.create_campaign("sweep", "c", "{}", false, {job("same"), job("other")});
  auto c3_counts = store.counts(c3);
  EXPECT_EQ(c3_counts.cached, 1);
  EXPECT_EQ(c3_counts.queued, 1);
}

TEST_F(StoreTest, FinishingACancelledJobStoresNothing) {
  auto c = store.create_campaign("sweep", "a", "{}", false, {job("x")});
  auto j = store.claim_job("local");
  EXPECT_EQ(store.cancel_campaign(c), CancelOutcome::cancelled);
  EXPECT_FALSE(store.finish_success(j->id, result_for(*j, 1)));
  EXPECT_FALSE(store.result("x"));
  EXPECT_EQ(store.job_state(j->id), kCancelled);
  EXPECT_EQ(store.cancel_campaign(c), CancelOutcome::already_finished);
  EXPECT_EQ(store.cancel_campaign(999), CancelOutcome::not_found);
}

TEST_F(StoreTest, FailuresAreRetriedUpToTheLimitThenKept) {
  store.create_campaign("sweep", "a", "{}", false, {job("f")});
  for (int attempt = 1; attempt <= 3; ++attempt) {
    auto j = store.claim_job("local");
    ASSERT_TRUE(j) << "attempt " << attempt;
    EXPECT_EQ(j->attempts, attempt);
    auto outcome = store.finish_failure(j->id, std::to_string(attempt), true, 3);
    EXPECT_EQ(outcome, attempt < 3 ? FailOutcome::requeued : FailOutcome::failed);
  }
  EXPECT_FALSE(store.claim_job("local"));
  auto j = store.job(1);
  EXPECT_EQ(j->state, kFailed);
  EXPECT_EQ(j->error, "3");
}

TEST_F(StoreTest, NonRetryableFailureFailsAtOnceAndRequeueDoesNotCountAnAttempt) {
  store.create_campaign("sweep", "a", "{}", false, {job("a"), job("b")});
  auto a = store.claim_job("local");
  EXPECT_EQ(store.finish_failure(a->id, "invalid", false, 3), FailOutcome::failed);
  auto b = store.claim_job("local");
  store.set_handle(b->id, "1234");
  store.requeue(b->id, "server restart");
  auto again = store.job(b->id);
  EXPECT_EQ(again->state, kQueued);
  EXPECT_EQ(again->attempts, 0);
  EXPECT_FALSE(again->handle);
}

TEST_F(StoreTest, ResultQueriesFilterByTestAndRanges) {
  store.create_campaign("sweep", "a", "{}", false, {job("p1", 10, 10), job("p2", 20, 30)});
  while (auto j = store.claim_job("local")) store.finish_success(j->id, result_for(*j, j->fr0));
  ResultFilter f;
  f.test = "uct";
  f.fr0_min = 15;
  auto rows = store.results(f);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].fs0, 30);
  f.test = "btt";
  EXPECT_TRUE(store.results(f).empty());
  EXPECT_EQ(store.durations().count, 2);
}

// A job pending in an executor's scheduler (Slurm) shows queued but stays the executor's: no
// worker claims it, nor its twin; it can finish, fail, be cancelled there, and is counted apart.
TEST_F(StoreTest, JobsPendingInAnExecutorsSchedulerShowQueuedButStayOwned) {
  store.create_campaign("sweep", "c", "{}", false, {job("a"), job("a"), job("b")});
  auto first = store.claim_job("slurm");
  ASSERT_TRUE(first);
  store.set_handle(first->id, "101");
  EXPECT_TRUE(store.set_pending(first->id, true));
  EXPECT_EQ(store.job_state(first->id), "queued");
  auto next = store.claim_job("slurm");  // not the pending job, nor its twin "a"
  ASSERT_TRUE(next);
  EXPECT_EQ(next->hash, "b");
  EXPECT_FALSE(store.claim_job("slurm"));
  auto counts = store.executor_counts();
  ASSERT_EQ(counts.size(), 2u);
  EXPECT_EQ(counts[0].executor, "");
  EXPECT_EQ(counts[0].waiting, 1);  // the twin
  EXPECT_EQ(counts[1].executor, "slurm");
  EXPECT_EQ(counts[1].pending, 1);
  EXPECT_EQ(counts[1].running, 1);
  EXPECT_EQ(store.owned_jobs().size(), 2u);
  EXPECT_EQ(store.counts().queued, 2);

  EXPECT_TRUE(store.set_pending(first->id, false));
  EXPECT_EQ(store.job_state(first->id), "running");
  EXPECT_TRUE(store.set_pending(first->id, true));
  EXPECT_TRUE(store.finish_success(first->id, result_for(*first, 5)));  // straight from PENDING
  EXPECT_EQ(store.job_state(first->id), "succeeded");
  EXPECT_FALSE(store.set_pending(first->id, true)) << "a finished job is nobody's";
  EXPECT_EQ(store.counts().succeeded, 2) << "the twin is answered by the result";

  // Without a handle a queued job would be claimable, i.e. submitted a second time.
  EXPECT_FALSE(store.set_pending(next->id, true));
  EXPECT_EQ(store.job_state(next->id), "running");
}

TEST_F(StoreTest, AJobCancelledInTheSchedulerIsCancelledWithTheReason) {
  store.create_campaign("sweep", "c", "{}", false, {job("a")});
  auto j = store.claim_job("slurm");
  ASSERT_TRUE(j);
  store.set_handle(j->id, "7");
  store.set_pending(j->id, true);
  EXPECT_TRUE(store.finish_cancelled(j->id, "Slurm job 7 was cancelled in Slurm (CANCELLED)"));
  auto row = store.job(j->id);
  EXPECT_EQ(row->state, "cancelled");
  EXPECT_EQ(row->error, "Slurm job 7 was cancelled in Slurm (CANCELLED)");
  EXPECT_FALSE(store.finish_cancelled(j->id, "again"));
}

}  // namespace
}  // namespace rockcal::db
