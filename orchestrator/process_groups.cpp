#include "orchestrator/process_groups.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <thread>

namespace rockcal::orch {
namespace {

// /proc/PID/stat: "pid (comm) state ppid pgrp ..."; comm may hold spaces and parentheses.
bool read_stat(const std::filesystem::path& dir, ProcessInfo& info) {
  std::ifstream in(dir / "stat");
  std::string line;
  if (!std::getline(in, line)) return false;
  auto close = line.rfind(')');
  if (close == std::string::npos) return false;
  std::istringstream rest(line.substr(close + 2));
  long ppid = 0, pgrp = 0;
  rest >> info.state >> ppid >> pgrp;
  info.pgid = static_cast<pid_t>(pgrp);
  return static_cast<bool>(rest);
}

std::string read_cmdline(const std::filesystem::path& dir) {
  std::ifstream in(dir / "cmdline", std::ios::binary);
  std::string raw((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (char& ch : raw) {
    if (ch == '\0') ch = ' ';
  }
  return raw;
}

}  // namespace

namespace {

// Every live (non-zombie) process for which `keep` holds.
std::vector<ProcessInfo> live_processes(const std::function<bool(const ProcessInfo&)>& keep) {
  std::vector<ProcessInfo> out;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    ProcessInfo info;
    info.pid = static_cast<pid_t>(std::stol(name));
    try {
      if (!read_stat(entry.path(), info) || info.state == 'Z') continue;
      info.cmdline = read_cmdline(entry.path());
    } catch (const std::exception&) {
      continue;  // the process exited while we read it (libstdc++ throws ESRCH from underflow)
    }
    if (keep(info)) out.push_back(std::move(info));
  }
  return out;
}

}  // namespace

std::vector<ProcessInfo> group_members(pid_t pgid) {
  return live_processes([pgid](const ProcessInfo& p) { return p.pgid == pgid; });
}

std::vector<pid_t> groups_mentioning(const std::string& needle) {
  pid_t own = getpgrp();
  std::set<pid_t> groups;
  for (const auto& p : live_processes([&](const ProcessInfo& p) {
         return p.pgid != own && p.cmdline.find(needle) != std::string::npos;
       })) {
    groups.insert(p.pgid);
  }
  return {groups.begin(), groups.end()};
}

bool group_runs_engine(pid_t pgid, const std::string& engine_name) {
  for (const auto& p : group_members(pgid)) {
    for (const char* marker : {"mpirun", "orterun", "mpiexec", "prterun"}) {
      if (p.cmdline.find(marker) != std::string::npos) return true;
    }
    if (!engine_name.empty() && p.cmdline.find(engine_name) != std::string::npos) return true;
  }
  return false;
}

namespace {

bool wait_group_gone(pid_t pgid, std::chrono::milliseconds limit) {
  auto deadline = std::chrono::steady_clock::now() + limit;
  while (true) {
    if (group_members(pgid).empty()) return true;
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

}  // namespace

bool terminate_group(pid_t pgid, std::chrono::milliseconds grace) {
  if (pgid <= 1) return false;  // never signal "every process" or init's group
  if (kill(-pgid, SIGTERM) != 0 && errno == ESRCH) return true;
  if (wait_group_gone(pgid, grace)) return true;
  kill(-pgid, SIGKILL);
  return wait_group_gone(pgid, std::chrono::seconds(5));
}

}  // namespace rockcal::orch
