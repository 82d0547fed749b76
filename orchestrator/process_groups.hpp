// Process-group facts read from /proc, for finding and stopping orphaned engine runs.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <string>
#include <vector>

namespace rockcal::orch {

struct ProcessInfo {
  pid_t pid = 0;
  pid_t pgid = 0;
  char state = '?';     // 'Z' for a zombie (dead, not yet reaped)
  std::string cmdline;  // argv joined by spaces
};

// Live (non-zombie) processes whose process group is `pgid`.
std::vector<ProcessInfo> group_members(pid_t pgid);

// Process groups (other than our own) with a live member whose command line contains `needle`.
std::vector<pid_t> groups_mentioning(const std::string& needle);

// True if any live member of the group runs the engine or an MPI launcher (so a pgid recorded
// by a dead server is not mistaken for an unrelated group that reuses the number).
bool group_runs_engine(pid_t pgid, const std::string& engine_name);

// SIGTERM to the group, wait up to `grace` for it to empty, then SIGKILL and wait again.
// Returns true if the group is gone.
bool terminate_group(pid_t pgid, std::chrono::milliseconds grace);

}  // namespace rockcal::orch
