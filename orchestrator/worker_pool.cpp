#include "orchestrator/worker_pool.hpp"

#include <algorithm>
#include <cctype>
#include <iostream>

#include "orchestrator/job_files.hpp"

namespace rockcal::orch {

using Clock = std::chrono::steady_clock;

void FailureCounts::add(const std::string& reason) {
  std::lock_guard lock(mutex_);
  ++counts_[reason];
}

std::map<std::string, std::int64_t> FailureCounts::snapshot() const {
  std::lock_guard lock(mutex_);
  return counts_;
}

WorkerPool::WorkerPool(db::Store& store, Executor& executor, PoolConfig config,
                       std::function<void(std::int64_t)> on_job_done)
    : store_(store),
      executor_(executor),
      config_(std::move(config)),
      on_job_done_(std::move(on_job_done)) {}

void WorkerPool::start() {
  for (int i = 0; i < config_.workers; ++i) {
    threads_.emplace_back([this](std::stop_token stop) { work(stop); });
  }
}

void WorkerPool::stop() {
  for (auto& t : threads_) t.request_stop();
  wake();
  threads_.clear();  // joins
}

void WorkerPool::wake() {
  {
    std::lock_guard lock(mutex_);
    ++wake_count_;
  }
  wake_cv_.notify_all();
}

void WorkerPool::resume(const db::JobRow& job, const std::string& handle) {
  std::lock_guard lock(mutex_);
  resumed_.emplace_back(job, handle);
}

void WorkerPool::fail(const db::JobRow& job, const std::string& reason, const std::string& error,
                      bool retryable, std::stop_token stop) {
  failures_.add(reason);
  store_write([&] { store_.finish_failure(job.id, error, retryable, config_.max_attempts); }, stop);
}

bool WorkerPool::store_write(const std::function<void()>& write, std::stop_token stop) {
  return write_with_retry(store_, write, config_.storage_retry, stop);
}

void WorkerPool::work(std::stop_token stop) {
  while (!stop.stop_requested()) {
    std::uint64_t seen;
    std::optional<std::pair<db::JobRow, std::string>> resumed;
    {
      std::lock_guard lock(mutex_);
      seen = wake_count_;
      if (!resumed_.empty()) {
        resumed = std::move(resumed_.front());
        resumed_.pop_front();
      }
    }
    std::optional<db::JobRow> job;
    if (resumed) {
      job = resumed->first;
    } else {
      try {
        job = store_.claim_job(executor_.name());
      } catch (const db::SqliteError& e) {
        if (store_.note_failure(e).empty())
          std::cerr << "rockcal: claiming a job failed: " << e.what() << "\n";
      } catch (const std::exception& e) {
        std::cerr << "rockcal: claiming a job failed: " << e.what() << "\n";
      }
    }
    if (job) {
      try {
        if (resumed) {
          monitor(*job, job_dir(config_.jobs_dir, job->id), resumed->second, stop);
        } else {
          execute(*job, stop);
        }
      } catch (const std::exception& e) {
        // A store error mid-job (e.g. a full disk) must not take the server down; execute() has
        // stopped the job, which counts as a failed attempt (so a persistent error cannot loop).
        std::cerr << "rockcal: job " << job->id << ": " << e.what() << "\n";
        try {
          fail(*job, "worker_error", std::string("worker error: ") + e.what(), true, stop);
        } catch (const std::exception&) {
          // Still running in the store; the next start-up re-queues it.
        }
        on_job_done_(job->id);
      }
      continue;
    }
    // Nothing queued: sleep until woken (new campaign, retry) or a periodic re-check.
    std::unique_lock lock(mutex_);
    wake_cv_.wait_for(lock, stop, std::chrono::seconds(1), [&] { return wake_count_ != seen; });
  }
}

namespace {

std::string failure_text(const std::string& what, const std::filesystem::path& dir) {
  std::string tail = tail_file(dir / "log", 20, 4000);
  return tail.empty() ? what : what + "; last log lines:\n" + tail;
}

}  // namespace

void WorkerPool::execute(const db::JobRow& job, std::stop_token stop) {
  std::filesystem::path dir;
  std::string handle;
  try {
    // A job directory that cannot be written may be a passing fault (a full or remounted disk):
    // tried again with back-off before the attempt counts as failed.
    auto backoff = config_.start_backoff;
    for (int tries = 1;; ++tries, backoff *= 2) {
      try {
        dir = prepare_job_dir(config_.jobs_dir, job);
        break;
      } catch (const std::exception&) {
        if (tries >= config_.start_tries || !pause_unless_stopped(backoff, stop)) throw;
      }
    }
    LaunchRequest request{
        dir, dir / "log", {"run", (dir / "job.json").string(), "--out", dir.string()}};
    handle = executor_.launch(request);
    store_.set_handle(job.id, handle);
  } catch (const std::exception& e) {
    if (!handle.empty()) executor_.cancel(handle);
    fail(job, "start", std::string("could not start: ") + e.what(), true, stop);
    on_job_done_(job.id);
    wake();  // it may have been re-queued
    return;
  }

  try {
    monitor(job, dir, handle, stop);
  } catch (...) {
    executor_.cancel(handle);  // never leave a job running that nobody watches
    throw;
  }
}

void WorkerPool::monitor(const db::JobRow& job, const std::filesystem::path& dir,
                         const std::string& handle, std::stop_token stop) {
  auto started = Clock::now();
  auto next_cancel_check = started + config_.cancel_check_interval;
  auto next_progress = started + config_.progress_interval;
  std::optional<double> last_progress;
  bool timed_out = false;
  // What the store shows: a job that waits in the executor's scheduler is queued there.
  bool shown_pending = job.state == db::kQueued;
  ExitStatus status;
  // Polls soon after the launch and then less often, up to poll_interval: a diagnosis runs
  // thousands of jobs of 10-100 ms, which a fixed 100 ms poll held for 100 ms each (a demo
  // diagnosis took 542 s with it, 431 s without), while an hour-long run needs no faster look.
  auto interval = std::min(config_.poll_interval, config_.first_poll_interval);
  while (true) {
    status = executor_.poll(handle);
    if (status.finished) break;
    auto now = Clock::now();
    if (status.pending != shown_pending) {
      store_write([&] { store_.set_pending(job.id, status.pending); }, stop);
      shown_pending = status.pending;
      // The job timeout counts run time, not time spent waiting in the scheduler's queue.
      if (!status.pending) started = now;
    }
    if (stop.stop_requested()) {
      // A scheduler's job goes on without us; the next server re-attaches to it.
      if (executor_.jobs_outlive_server()) return;
      executor_.cancel(handle);
      try {
        store_.requeue(job.id, "server stopped while the job ran");
      } catch (const db::SqliteError& e) {
        // Still running in the store; the next start-up re-queues it.
        store_.note_failure(e);
      }
      return;
    }
    if (now >= next_cancel_check) {
      next_cancel_check = now + config_.cancel_check_interval;
      auto state = store_.job_state(job.id);
      if (state != db::kRunning && state != db::kQueued) {  // cancelled with its campaign
        executor_.cancel(handle);
        on_job_done_(job.id);
        return;
      }
    }
    if (now >= next_progress) {
      next_progress = now + config_.progress_interval;
      auto p = read_progress(dir);
      try {
        if (p && p != last_progress) store_.set_progress(job.id, *p);
        last_progress = p;
      } catch (const db::SqliteError& e) {
        if (store_.note_failure(e).empty()) throw;  // progress can wait for the next look
      }
    }
    if (!status.pending && now - started > config_.job_timeout) {
      status = executor_.cancel(handle);
      timed_out = true;
      break;
    }
    std::this_thread::sleep_for(interval);
    interval = std::min(config_.poll_interval,
                        std::chrono::duration_cast<std::chrono::milliseconds>(interval * 3 / 2) +
                            std::chrono::milliseconds(1));
  }

  if (timed_out) {
    auto seconds = std::chrono::duration_cast<std::chrono::seconds>(config_.job_timeout).count();
    fail(job, "job_timeout", failure_text("timed out after " + std::to_string(seconds) + " s", dir),
         true, stop);
  } else if (status.ending == Ending::failed) {
    // The scheduler's verdict (Slurm TIMEOUT, NODE_FAIL, ...): retried like any failed run.
    std::string reason = status.scheduler_state;
    for (char& c : reason) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    fail(job, reason, failure_text(status.reason, dir), true, stop);
  } else if (status.ending == Ending::cancelled) {
    store_write([&] { store_.finish_cancelled(job.id, status.reason); }, stop);
  } else if (status.ending == Ending::requeue) {
    store_write([&] { store_.requeue(job.id, status.reason); }, stop);
    wake();
  } else if (status.exit_code == 0 && status.signal == 0) {
    std::optional<db::ResultRow> result;
    try {
      result = read_result(dir, job);
    } catch (const std::exception& e) {
      fail(job, "no_result", failure_text(std::string("exit 0 but ") + e.what(), dir), true, stop);
    }
    // A result that cannot be stored now (a full disk, a held lock) is stored once it can.
    if (result) store_write([&] { store_.finish_success(job.id, *result); }, stop);
  } else {
    // Exit 2 is an invalid spec: running it again cannot help.
    bool retryable = !(status.signal == 0 && status.exit_code == 2);
    fail(job, status.signal ? "signal" : "exit_code",
         failure_text("engine " + status.describe(), dir), retryable, stop);
  }
  on_job_done_(job.id);
}

}  // namespace rockcal::orch
