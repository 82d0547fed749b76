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

struct ExitStatus {
  bool finished = false;
  int exit_code = -1;  // when exited normally
  int signal = 0;      // when killed by a signal
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
};

}  // namespace rockcal::orch
