// Slurm's view of a job, read from squeue / sacct / sbatch output, and how its states map onto
// rockcal's job states.
#pragma once

#include <map>
#include <string>
#include <string_view>

namespace rockcal::orch::slurm {

// What a Slurm job state means for rockcal.
enum class Phase {
  pending,    // PENDING, REQUEUED, ...: rockcal shows the job queued
  running,    // RUNNING, COMPLETING, SUSPENDED, ...: still going
  completed,  // COMPLETED: the batch script exited 0
  failed,     // FAILED, TIMEOUT, NODE_FAIL, OUT_OF_MEMORY, ...: a failed attempt with that reason
  cancelled,  // CANCELLED
  requeue,    // PREEMPTED (and not requeued by Slurm itself): rockcal submits it again
};

// Accepts squeue's and sacct's spellings ("CANCELLED by 0", "OUT_OF_MEMORY", "RUNNING+"). A state
// this list does not know is treated as running: a new Slurm state must not end a job.
Phase phase_of(std::string_view state);

struct JobState {
  std::string state;   // e.g. "TIMEOUT"
  std::string reason;  // squeue's %r (e.g. "TimeLimit", "Resources"), or sacct's exit code
};

// Lines of `squeue --noheader --format=%i|%T|%r`, keyed by job id. Array and het-job lines (ids
// with '_' or '+') are not rockcal's and are skipped.
std::map<std::string, JobState> parse_squeue(const std::string& out);
// Lines of `sacct --noheader --parsable2 --allocations --format=JobIDRaw,State,ExitCode`.
std::map<std::string, JobState> parse_sacct(const std::string& out);
// `sbatch --parsable` prints "ID" or "ID;CLUSTER"; returns the ID. Throws std::runtime_error on
// anything else.
std::string parse_sbatch_id(const std::string& out);
// True for a Slurm job id (digits only): handles are passed to Slurm's commands.
bool is_job_id(std::string_view s);

}  // namespace rockcal::orch::slurm
