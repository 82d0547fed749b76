// The Slurm executor: each job is a batch job (sbatch --parsable) whose script, in the job's
// directory on a filesystem the compute nodes share, runs `srun rockcal-dem run job.json --out
// DIR` and then writes its own completion marker with the exit status. Jobs are tracked with one
// squeue query for all of them (sacct for those squeue has forgotten) at most every
// query_interval, cancelled with scancel, and outlive the server: a restarted one re-attaches.
#pragma once

#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>

#include "orchestrator/executor.hpp"
#include "orchestrator/slurm/states.hpp"

namespace rockcal::orch::slurm {

struct SlurmConfig {
  std::string engine = "rockcal-dem";  // absolute path, the same on every compute node
  int ranks = 1;                       // --ntasks: MPI ranks per job, started by srun
  // srun --mpi: the engine is an MPI program, and Open MPI started by srun needs Slurm's PMIx
  // even for one rank. Empty: the cluster's MpiDefault.
  std::string srun_mpi = "pmix";
  std::string partition;  // empty: the cluster's default
  std::string account;
  std::string time_limit;  // sbatch --time (e.g. "30", "2:00:00"); empty: the partition's
  std::chrono::milliseconds query_interval{10000};  // the shortest time between squeue queries
  std::chrono::milliseconds cancel_timeout{60000};  // scancel until Slurm reports the job ended
};

// Files the batch script writes in the job directory.
inline constexpr const char* kExitStatusFile = "exit-status";  // the completion marker
inline constexpr const char* kSlurmIdFile = "slurm-job-id";    // written right after sbatch
inline constexpr const char* kBatchScriptFile = "job.sbatch";

// The batch script for a job (exposed for tests).
std::string batch_script(const SlurmConfig& config, const LaunchRequest& request);

// Slurm's answer for one job at the last query, as the executor sees it (exposed for tests).
struct Observation {
  std::optional<JobState> slurm;   // nullopt: neither squeue nor sacct knows the job
  std::optional<int> marker_exit;  // the exit status the batch script wrote, if it did
};
// Turns what is known about a job into its status. `handle` only names it in reasons.
ExitStatus status_from(const std::string& handle, const Observation& seen);

class SlurmExecutor : public Executor {
 public:
  explicit SlurmExecutor(SlurmConfig config) : config_(std::move(config)) {}
  std::string name() const override { return "slurm"; }
  std::string launch(const LaunchRequest& request) override;
  ExitStatus poll(const std::string& handle) override;
  ExitStatus cancel(const std::string& handle) override;
  bool stop_orphan(const std::optional<std::string>& handle,
                   const std::filesystem::path& job_dir) override;
  bool jobs_outlive_server() const override { return true; }
  std::optional<std::string> reattach(const std::optional<std::string>& handle,
                                      const std::filesystem::path& job_dir) override;

  // squeue/sacct runs so far (for tests of the throttling and for logs).
  std::int64_t queries() const;

 private:
  struct Watched {
    std::filesystem::path dir;
    std::chrono::steady_clock::time_point since;  // a query older than this cannot speak for it
    ExitStatus last;                              // what poll() said last (while nothing newer)
  };
  // Re-runs the batched query if the last one is older than `max_age`. Called with mutex_ held.
  void refresh(std::chrono::milliseconds max_age);
  ExitStatus status_locked(const std::string& handle, std::chrono::milliseconds max_age);
  // The Slurm job of a job directory, when its handle never reached the store.
  std::optional<std::string> find_by_directory(const std::filesystem::path& job_dir);

  SlurmConfig config_;
  mutable std::mutex mutex_;
  std::map<std::string, Watched> watched_;  // by Slurm job id
  std::map<std::string, JobState> known_;   // the last query's answers
  std::chrono::steady_clock::time_point last_query_{};
  bool last_query_ok_ = false;
  std::chrono::steady_clock::time_point last_warning_{};
  std::int64_t queries_ = 0;
};

}  // namespace rockcal::orch::slurm
