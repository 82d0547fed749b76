// The store: campaigns, jobs and results in one SQLite file. Thread-safe: each call borrows a
// connection from a small pool, so readers run concurrently (WAL) and writers queue on the
// busy timeout inside BEGIN IMMEDIATE transactions.
#pragma once

#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "db/records.hpp"
#include "db/sqlite.hpp"
#include "db/storage_faults.hpp"

namespace rockcal::db {

enum class CancelOutcome { not_found, already_finished, cancelled };

// What happened to a running job that failed.
enum class FailOutcome { requeued, failed, not_running };

class Store {
 public:
  // Opens or creates the database and applies pending migrations. A write waits up to
  // `busy_timeout_ms` for another writer's lock before it fails with SQLITE_BUSY.
  explicit Store(std::string path, int busy_timeout_ms = 10000);
  ~Store();

  const std::string& path() const { return path_; }

  // ---- writes (store.cpp) ----

  // Creates a campaign and its jobs in one transaction. A job whose hash already has a result is
  // created succeeded and cached: it is answered from the store, not run again (a stored run
  // without a peak answers it as failed, with that reason).
  std::int64_t create_campaign(const std::string& kind, const std::string& name,
                               const std::string& request, bool has_driver,
                               const std::vector<NewJob>& jobs);

  // Adds one job to an existing campaign (for driver threads). Returns the job id; the job is
  // created cancelled when the campaign has been cancelled, cached when its result is known.
  std::int64_t add_job(std::int64_t campaign_id, const NewJob& job);

  // Atomically claims the oldest queued job (one UPDATE ... RETURNING), marking it running.
  // Skips jobs whose identical twin is already running: that run will answer both.
  std::optional<JobRow> claim_job(const std::string& executor);

  void set_handle(std::int64_t job_id, const std::string& handle);
  void set_progress(std::int64_t job_id, double fraction);

  // Marks a running job succeeded and records its result, in one transaction; queued jobs with the
  // same hash are answered too. A result with `no_peak` marks them failed with the error
  // no_peak_error(reason) instead, never retried. Returns false (and stores nothing) if the job is
  // no longer running (it was cancelled meanwhile).
  bool finish_success(std::int64_t job_id, const ResultRow& result);

  // A running job failed: re-queued while attempts < max_attempts and `retryable`, else failed.
  FailOutcome finish_failure(std::int64_t job_id, const std::string& error, bool retryable,
                             int max_attempts);

  // Puts a running job back in the queue without counting the attempt (server shutdown or crash).
  void requeue(std::int64_t job_id, const std::string& note);

  // A job an executor owns (it has a handle) waits in that executor's scheduler (pending: shown
  // queued, not claimable) or runs there. False if the job is no longer the executor's.
  bool set_pending(std::int64_t job_id, bool pending);

  // An owned job was cancelled outside rockcal (e.g. scancel by an operator): cancelled, `note`
  // as its error. False if the job is no longer the executor's.
  bool finish_cancelled(std::int64_t job_id, const std::string& note);

  CancelOutcome cancel_campaign(std::int64_t campaign_id);

  void set_driver_status(std::int64_t campaign_id, const std::string& status,
                         const std::optional<std::string>& summary);

  // ---- reads (store_queries.cpp) ----

  std::optional<CampaignRow> campaign(std::int64_t id);
  std::vector<CampaignRow> campaigns(std::int64_t limit, std::int64_t offset);
  std::int64_t campaign_count();
  StateCounts counts(std::optional<std::int64_t> campaign_id = std::nullopt);
  std::vector<JobRow> running_jobs(std::optional<std::int64_t> campaign_id = std::nullopt);
  // Jobs an executor owns: running, or queued in its scheduler (with a handle). By id.
  std::vector<JobRow> owned_jobs();
  // Unfinished jobs by executor, for /metrics.
  std::vector<ExecutorCounts> executor_counts();
  std::optional<JobRow> job(std::int64_t id);
  std::string job_state(std::int64_t id);  // "" if no such job
  // A campaign's jobs with their results, by job id: `limit` of them (-1: all) from `offset`.
  std::vector<JobResultRow> campaign_results(std::int64_t campaign_id, std::int64_t limit = -1,
                                             std::int64_t offset = 0);
  std::optional<ResultRow> result(const std::string& hash);
  std::vector<ResultRow> results(const ResultFilter& filter);
  DurationStats durations(std::optional<std::int64_t> campaign_id = std::nullopt);
  // Histogram counts of run durations, for the given upper bounds (cumulative, Prometheus style).
  std::vector<std::int64_t> duration_buckets(const std::vector<double>& upper_bounds);

  // Runs `fn` on a pooled connection (for tests and one-off maintenance such as integrity checks).
  void with_connection(const std::function<void(Connection&)>& fn);

  // ---- storage faults (storage_faults.hpp) ----

  // Records a failed write: its storage fault kind ("" when it is none, e.g. a constraint).
  std::string note_failure(const SqliteError& e);
  // Records a write that succeeded: the fault in force, if any, has cleared.
  void note_success() { health_.succeeded(); }
  const StorageHealth& health() const { return health_; }
  // Whether the database takes a write now: a one-value write committed, waiting at most 100 ms
  // for another writer's lock. Records the outcome; returns the fault in force.
  std::optional<StorageFault> probe_write();

 private:
  class Lease;
  Lease lease();
  void give_back(std::unique_ptr<Connection> conn);

  std::string path_;
  int busy_timeout_ms_;
  StorageHealth health_;
  std::mutex pool_mutex_;
  std::vector<std::unique_ptr<Connection>> idle_;
};

// A borrowed connection, returned to the pool when it goes out of scope.
class Store::Lease {
 public:
  Lease(Store& store, std::unique_ptr<Connection> conn) : store_(store), conn_(std::move(conn)) {}
  ~Lease() {
    if (conn_) store_.give_back(std::move(conn_));
  }
  Lease(Lease&& other) noexcept : store_(other.store_), conn_(std::move(other.conn_)) {}
  Connection& operator*() { return *conn_; }
  Connection* operator->() { return conn_.get(); }

 private:
  Store& store_;
  std::unique_ptr<Connection> conn_;
};

// Seconds since the Unix epoch, as stored in the *_at columns.
double now_seconds();

// The error of a job whose run ended without a peak: "no peak: <reason>".
std::string no_peak_error(const std::string& reason);

}  // namespace rockcal::db
