// The worker pool: N threads, each claiming a queued job from the store, running it through the
// executor and recording its outcome (result, retry, or failure with the last log lines).
#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

#include "db/store.hpp"
#include "orchestrator/executor.hpp"
#include "orchestrator/storage_retry.hpp"

namespace rockcal::orch {

// Failed attempts by reason since the server started ("exit_code", "signal", "job_timeout",
// "no_result", "start", "worker_error", or a scheduler's state such as "timeout", "node_fail").
// Storage faults a write met (and retried) are counted by the store (Store::health()).
class FailureCounts {
 public:
  void add(const std::string& reason);
  std::map<std::string, std::int64_t> snapshot() const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, std::int64_t> counts_;
};

struct PoolConfig {
  int workers = 1;
  int max_attempts = 3;  // first run + retries
  std::chrono::milliseconds job_timeout{std::chrono::hours(6)};
  std::filesystem::path jobs_dir;                // absolute; a directory per job
  std::chrono::milliseconds poll_interval{100};  // the longest wait between looks at a running job
  std::chrono::milliseconds first_poll_interval{1};  // the first wait; x1.5 after each look
  std::chrono::milliseconds cancel_check_interval{300};
  std::chrono::milliseconds progress_interval{1000};
  // Store writes that meet a storage fault are tried until they succeed (a job's outcome is
  // never dropped), with this back-off.
  StorageRetry storage_retry;
  // A job directory that cannot be prepared (a transient filesystem fault) is tried start_tries
  // times, waiting start_backoff, doubled after each try, before the attempt counts as failed.
  int start_tries = 5;
  std::chrono::milliseconds start_backoff{250};
};

class WorkerPool {
 public:
  // `on_job_done` is called after a job reached an end state (or was re-queued).
  WorkerPool(db::Store& store, Executor& executor, PoolConfig config,
             std::function<void(std::int64_t job_id)> on_job_done);
  ~WorkerPool() { stop(); }

  void start();
  // Stops every worker; jobs still running are stopped and put back in the queue.
  void stop();
  // Tells idle workers there may be new work.
  void wake();
  // Hands a job a previous server launched (re-attached by the executor) to the next free
  // worker, which watches it to its end as if it had launched it. Before start().
  void resume(const db::JobRow& job, const std::string& handle);

  const FailureCounts& failures() const { return failures_; }

 private:
  void work(std::stop_token stop);
  void execute(const db::JobRow& job, std::stop_token stop);
  // Records a failed attempt (counted by `reason`), through store_write.
  void fail(const db::JobRow& job, const std::string& reason, const std::string& error,
            bool retryable, std::stop_token stop);
  // Runs a store write through write_with_retry (storage_retry.hpp) until it succeeds or the pool
  // stops. False when stopped first: the job then stays running in the store, and the next
  // start-up re-queues it.
  bool store_write(const std::function<void()>& write, std::stop_token stop);
  // Watches a launched job until it ends, is cancelled or times out, and records the outcome.
  void monitor(const db::JobRow& job, const std::filesystem::path& dir, const std::string& handle,
               std::stop_token stop);

  db::Store& store_;
  Executor& executor_;
  PoolConfig config_;
  std::function<void(std::int64_t)> on_job_done_;
  std::mutex mutex_;
  std::condition_variable_any wake_cv_;
  std::uint64_t wake_count_ = 0;
  std::deque<std::pair<db::JobRow, std::string>> resumed_;  // guarded by mutex_
  FailureCounts failures_;
  std::vector<std::jthread> threads_;
};

}  // namespace rockcal::orch
