// The store's writes. Every write is one BEGIN IMMEDIATE transaction (or one atomic statement).
#include "db/store.hpp"

#include <chrono>
#include <filesystem>
#include <stdexcept>

#include "db/migrations.hpp"
#include "db/row_readers.hpp"

namespace rockcal::db {

using detail::kJobColumns;
using detail::read_job;

// A job an executor owns: running, or queued in the executor's own scheduler (it has a handle).
#define OWNED(t) \
  "(" t ".state = 'running' OR (" t ".state = 'queued' AND " t ".handle IS NOT NULL))"

std::string no_peak_error(const std::string& reason) {
  return "no peak: " + reason;
}

double now_seconds() {
  using namespace std::chrono;
  return duration<double>(system_clock::now().time_since_epoch()).count();
}

Store::Store(std::string path, int busy_timeout_ms)
    : path_(std::move(path)), busy_timeout_ms_(busy_timeout_ms) {
  auto conn = std::make_unique<Connection>(path_, busy_timeout_ms_);
  migrate(*conn);
  give_back(std::move(conn));
}

Store::~Store() = default;

Store::Lease Store::lease() {
  {
    std::lock_guard lock(pool_mutex_);
    if (!idle_.empty()) {
      auto conn = std::move(idle_.back());
      idle_.pop_back();
      return Lease(*this, std::move(conn));
    }
  }
  return Lease(*this, std::make_unique<Connection>(path_, busy_timeout_ms_));
}

void Store::give_back(std::unique_ptr<Connection> conn) {
  std::lock_guard lock(pool_mutex_);
  // Keep a bounded number idle; a burst of concurrent requests may open more, briefly.
  if (idle_.size() < 64) idle_.push_back(std::move(conn));
}

void Store::with_connection(const std::function<void(Connection&)>& fn) {
  auto conn = lease();
  fn(*conn);
}

namespace {

// What the store knows of a job's identity: nothing (run it), a result, or a run without a peak
// (the same spec gives the same run: answered as failed, with its reason).
struct KnownResult {
  bool found = false;
  std::optional<std::string> no_peak;
};

KnownResult known_result(Connection& conn, const std::string& hash) {
  auto st = conn.prepare("SELECT no_peak FROM results WHERE hash = ?");
  st.bind_all(hash);
  if (!st.step()) return {};
  return {true, st.opt_text(0)};
}

std::int64_t insert_job(Connection& conn, std::int64_t campaign_id, const NewJob& job,
                        const char* forced_state) {
  const KnownResult known = forced_state ? KnownResult{} : known_result(conn, job.hash);
  const char* state = forced_state    ? forced_state
                      : !known.found  ? kQueued
                      : known.no_peak ? kFailed
                                      : kSucceeded;
  double now = now_seconds();
  auto st = conn.prepare(
      "INSERT INTO jobs (campaign_id, test, fr0, fs0, spec, hash, state, cached, created_at, "
      "finished_at, error) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  st.bind_all(campaign_id, job.test, job.fr0, job.fs0, job.spec, job.hash, state,
              known.found ? 1 : 0, now);
  st.bind(10, std::string(state) == kQueued ? std::optional<double>() : std::optional(now));
  st.bind(11, known.no_peak ? std::optional(no_peak_error(*known.no_peak)) : std::nullopt);
  st.run();
  return conn.last_insert_rowid();
}

}  // namespace

std::int64_t Store::create_campaign(const std::string& kind, const std::string& name,
                                    const std::string& request, bool has_driver,
                                    const std::vector<NewJob>& jobs) {
  auto conn = lease();
  Transaction tx(*conn);
  auto st = conn->prepare(
      "INSERT INTO campaigns (kind, name, request, created_at, driver_status) VALUES (?, ?, ?, ?, "
      "?)");
  st.bind_all(kind, name, request, now_seconds());
  st.bind(5, has_driver ? std::optional<std::string>("running") : std::nullopt);
  st.run();
  std::int64_t id = conn->last_insert_rowid();
  for (const auto& job : jobs) insert_job(*conn, id, job, nullptr);
  tx.commit();
  return id;
}

std::int64_t Store::add_job(std::int64_t campaign_id, const NewJob& job) {
  auto conn = lease();
  Transaction tx(*conn);
  auto st = conn->prepare("SELECT cancel_requested FROM campaigns WHERE id = ?");
  st.bind_all(campaign_id);
  if (!st.step()) throw std::invalid_argument("no campaign " + std::to_string(campaign_id));
  bool cancelled = st.int64(0) != 0;
  std::int64_t id = insert_job(*conn, campaign_id, job, cancelled ? kCancelled : nullptr);
  tx.commit();
  return id;
}

std::optional<JobRow> Store::claim_job(const std::string& executor) {
  // An explicit transaction, not one UPDATE ... RETURNING: with SQLite 3.40 that UPDATE was seen
  // to change a row and yet return none (sqlite3_changes() = 1, no row; two workers claiming),
  // which left a job "running" that no worker watched. BEGIN IMMEDIATE makes pick and claim one.
  auto conn = lease();
  Transaction tx(*conn);
  std::int64_t id = 0;
  {
    auto pick = conn->prepare(
        "SELECT id FROM jobs q WHERE q.state = 'queued' AND q.handle IS NULL AND NOT EXISTS ("
        "SELECT 1 FROM jobs r WHERE r.hash = q.hash AND " OWNED("r") ") ORDER BY q.id LIMIT 1");
    if (!pick.step()) return std::nullopt;
    id = pick.int64(0);
  }
  conn->prepare(
          "UPDATE jobs SET state = 'running', attempts = attempts + 1, started_at = ?, "
          "executor = ?, handle = NULL, progress = 0 WHERE id = ?")
      .bind_all(now_seconds(), executor, id)
      .run();
  std::optional<JobRow> row;
  {
    auto st = conn->prepare(std::string("SELECT ") + kJobColumns + " FROM jobs WHERE id = ?");
    st.bind_all(id);
    if (!st.step()) throw std::logic_error("claimed job " + std::to_string(id) + " vanished");
    row = read_job(st);
  }
  tx.commit();
  return row;
}

void Store::set_handle(std::int64_t job_id, const std::string& handle) {
  auto conn = lease();
  conn->prepare("UPDATE jobs SET handle = ? WHERE id = ?").bind_all(handle, job_id).run();
}

void Store::set_progress(std::int64_t job_id, double fraction) {
  auto conn = lease();
  conn->prepare("UPDATE jobs SET progress = ? WHERE id = ? AND state = 'running'")
      .bind_all(fraction, job_id)
      .run();
}

bool Store::finish_success(std::int64_t job_id, const ResultRow& r) {
  auto conn = lease();
  Transaction tx(*conn);
  double now = now_seconds();
  // A run without a peak is a failed job (deterministic: not retried), its result kept.
  const char* state = r.no_peak ? kFailed : kSucceeded;
  const std::optional<std::string> error =
      r.no_peak ? std::optional(no_peak_error(*r.no_peak)) : std::nullopt;
  conn->prepare(
          "UPDATE jobs SET state = ?, finished_at = ?, progress = 1, error = ? "
          "WHERE id = ? AND " OWNED("jobs"))
      .bind_all(state, now, error, job_id)
      .run();
  if (conn->changes() == 0) return false;
  // OR IGNORE: an identical job may have finished first (e.g. after a crash); its result stands.
  auto st = conn->prepare(
      "INSERT OR IGNORE INTO results (hash, job_id, test, fr0, fs0, peak_load, strength, "
      "youngs_modulus, poisson_ratio, particles, wall_seconds, engine_version, result, curve, "
      "created_at, no_peak) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  st.bind_all(r.hash, job_id, r.test, r.fr0, r.fs0, r.peak_load, r.strength, r.youngs_modulus,
              r.poisson_ratio, r.particles, r.wall_seconds, r.engine_version, r.result, r.curve,
              now, r.no_peak);
  st.run();
  conn->prepare(
          "UPDATE jobs SET state = ?, cached = 1, finished_at = ?, error = ? "
          "WHERE hash = ? AND state = 'queued' AND handle IS NULL")
      .bind_all(state, now, error, r.hash)
      .run();
  tx.commit();
  return true;
}

FailOutcome Store::finish_failure(std::int64_t job_id, const std::string& error, bool retryable,
                                  int max_attempts) {
  auto conn = lease();
  Transaction tx(*conn);
  auto st = conn->prepare("SELECT attempts FROM jobs WHERE id = ? AND " OWNED("jobs"));
  st.bind_all(job_id);
  if (!st.step()) return FailOutcome::not_running;
  bool retry = retryable && st.int64(0) < max_attempts;
  if (retry) {
    conn->prepare(
            "UPDATE jobs SET state = 'queued', error = ?, handle = NULL, progress = NULL "
            "WHERE id = ?")
        .bind_all(error, job_id)
        .run();
  } else {
    conn->prepare(
            "UPDATE jobs SET state = 'failed', error = ?, finished_at = ?, handle = NULL "
            "WHERE id = ?")
        .bind_all(error, now_seconds(), job_id)
        .run();
  }
  tx.commit();
  return retry ? FailOutcome::requeued : FailOutcome::failed;
}

void Store::requeue(std::int64_t job_id, const std::string& note) {
  auto conn = lease();
  conn->prepare(
          "UPDATE jobs SET state = 'queued', attempts = MAX(attempts - 1, 0), error = ?, "
          "handle = NULL, progress = NULL, started_at = NULL WHERE id = ? AND " OWNED("jobs"))
      .bind_all(note, job_id)
      .run();
}

bool Store::set_pending(std::int64_t job_id, bool pending) {
  auto conn = lease();
  conn->prepare("UPDATE jobs SET state = ? WHERE id = ? AND handle IS NOT NULL AND " OWNED("jobs"))
      .bind_all(pending ? kQueued : kRunning, job_id)
      .run();
  return conn->changes() > 0;
}

bool Store::finish_cancelled(std::int64_t job_id, const std::string& note) {
  auto conn = lease();
  conn->prepare(
          "UPDATE jobs SET state = 'cancelled', error = ?, finished_at = ?, handle = NULL "
          "WHERE id = ? AND " OWNED("jobs"))
      .bind_all(note, now_seconds(), job_id)
      .run();
  return conn->changes() > 0;
}

CancelOutcome Store::cancel_campaign(std::int64_t campaign_id) {
  auto conn = lease();
  Transaction tx(*conn);
  auto st = conn->prepare("SELECT driver_status FROM campaigns WHERE id = ?");
  st.bind_all(campaign_id);
  if (!st.step()) return CancelOutcome::not_found;
  bool driver_running = st.opt_text(0) == std::optional<std::string>("running");
  double now = now_seconds();
  conn->prepare(
          "UPDATE jobs SET state = 'cancelled', finished_at = ? "
          "WHERE campaign_id = ? AND state IN ('queued', 'running')")
      .bind_all(now, campaign_id)
      .run();
  bool stopped_jobs = conn->changes() > 0;
  if (!stopped_jobs && !driver_running) return CancelOutcome::already_finished;
  conn->prepare(
          "UPDATE campaigns SET cancel_requested = 1, driver_status = CASE WHEN driver_status = "
          "'running' THEN 'cancelled' ELSE driver_status END WHERE id = ?")
      .bind_all(campaign_id)
      .run();
  tx.commit();
  return CancelOutcome::cancelled;
}

void Store::set_driver_status(std::int64_t campaign_id, const std::string& status,
                              const std::optional<std::string>& summary) {
  auto conn = lease();
  conn->prepare(
          "UPDATE campaigns SET driver_status = ?, summary = COALESCE(?, summary) WHERE id = ?")
      .bind_all(status, summary, campaign_id)
      .run();
}

}  // namespace rockcal::db
