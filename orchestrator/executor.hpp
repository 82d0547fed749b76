// Where jobs run. The worker pool launches, polls and cancels through this interface only, so a
// Slurm executor can replace the local process pool without touching the pool.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace rockcal::orch {

struct LaunchRequest {
  std::filesystem::path job_dir;         // holds job.json; the run writes its files here
  std::filesystem::path log_file;        // stdout and stderr go here (appended)
  std::vector<std::string> engine_args;  // after the engine executable: run job.json --out DIR
};

// Who decided how a finished job ended.
enum class Ending {
  run,        // the run's own exit status (exit_code, signal) decides
  failed,     // the scheduler ended it (e.g. Slurm TIMEOUT, NODE_FAIL): a failed attempt
  cancelled,  // someone cancelled it outside rockcal (e.g. scancel by an operator)
  requeue,    // the scheduler dropped it without running it to the end (e.g. preempted): run again
};

struct ExitStatus {
  bool finished = false;
  bool pending = false;  // not finished: still waiting in the scheduler's queue, not started
  int exit_code = -1;    // when exited normally
  int signal = 0;        // when killed by a signal
  Ending ending = Ending::run;
  std::string scheduler_state;  // when the scheduler decided (e.g. "TIMEOUT"), its state name
  std::string reason;           // ... and a sentence saying so, for the job's error
  std::string describe() const;
};

class Executor {
 public:
  virtual ~Executor() = default;
  // Stored with each running job, so a restarted server knows which executor owns the handle.
  virtual std::string name() const = 0;
  // Starts the job; returns an opaque handle (stored in the database). Throws on failure to start.
  virtual std::string launch(const LaunchRequest& request) = 0;
  // Non-blocking.
  virtual ExitStatus poll(const std::string& handle) = 0;
  // Stops the job and waits until it is gone (gracefully first, then forcibly).
  virtual ExitStatus cancel(const std::string& handle) = 0;
  // After a server crash: stops whatever still runs for a job a previous server launched, found by
  // the handle it stored or (crash between launch and storing the handle) by the job directory.
  // Returns true if something was found and stopped.
  virtual bool stop_orphan(const std::optional<std::string>& handle,
                           const std::filesystem::path& job_dir) = 0;

  // True when jobs outlive the server (a batch scheduler's jobs): a stopping server leaves them
  // running, and the next one takes them over with reattach() instead of running them again.
  virtual bool jobs_outlive_server() const { return false; }
  // After a restart, for a job a previous server launched: the handle to go on watching it by
  // (found from the stored handle or, when that was never stored, from the job directory), or
  // nullopt when the executor has no such job (it is then run again). Throws when it cannot tell.
  virtual std::optional<std::string> reattach(const std::optional<std::string>& handle,
                                              const std::filesystem::path& job_dir) {
    (void)handle;
    (void)job_dir;
    return std::nullopt;
  }
};

}  // namespace rockcal::orch
