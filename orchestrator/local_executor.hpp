// The default executor: runs each job as a child process group on this machine, under
// `mpirun -np K` or (ranks = 0) the engine directly.
#pragma once

#include <chrono>
#include <map>
#include <mutex>

#include "orchestrator/executor.hpp"

namespace rockcal::orch {

struct LocalExecutorConfig {
  std::string engine = "rockcal-dem";  // path, or a name looked up in PATH
  int ranks = 1;                       // MPI ranks per job; 0 runs the engine without mpirun
  std::string mpirun = "mpirun";
  std::chrono::milliseconds grace{5000};  // between SIGTERM and SIGKILL
  // mpirun --hostfile: ranks on several hosts. Each host needs the engine at the same path and the
  // job directory on a shared filesystem (docs/operations.md).
  std::string hostfile;
};

class LocalExecutor : public Executor {
 public:
  explicit LocalExecutor(LocalExecutorConfig config) : config_(std::move(config)) {}
  std::string name() const override { return "local"; }
  std::string launch(const LaunchRequest& request) override;
  ExitStatus poll(const std::string& handle) override;
  ExitStatus cancel(const std::string& handle) override;
  bool stop_orphan(const std::optional<std::string>& handle,
                   const std::filesystem::path& job_dir) override;

  // The full argv a job runs with (exposed for tests and logs).
  std::vector<std::string> command(const LaunchRequest& request) const;

 private:
  ExitStatus reap(pid_t pid, bool block);

  LocalExecutorConfig config_;
  std::mutex mutex_;
  std::map<pid_t, ExitStatus> finished_;  // reaped children, until their pid is reused by a launch
};

}  // namespace rockcal::orch
