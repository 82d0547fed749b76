#include "orchestrator/local_executor.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <set>
#include <stdexcept>
#include <thread>

#include "orchestrator/process_groups.hpp"

namespace rockcal::orch {
namespace {

pid_t parse_handle(const std::string& handle) {
  std::size_t used = 0;
  long value = std::stol(handle, &used);
  if (used != handle.size() || value <= 1) throw std::invalid_argument("bad handle " + handle);
  return static_cast<pid_t>(value);
}

ExitStatus from_wait_status(int status) {
  ExitStatus s;
  s.finished = true;
  if (WIFEXITED(status)) s.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) s.signal = WTERMSIG(status);
  return s;
}

// Closes its descriptor on scope exit.
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) close(fd);
  }
};

}  // namespace

std::string ExitStatus::describe() const {
  if (!finished) return pending ? "waiting in the scheduler's queue" : "still running";
  if (!reason.empty()) return reason;
  if (signal)
    return std::string("killed by signal ") + std::to_string(signal) + " (" + strsignal(signal) +
           ")";
  return "exit code " + std::to_string(exit_code);
}

std::vector<std::string> LocalExecutor::command(const LaunchRequest& request) const {
  std::vector<std::string> argv;
  if (config_.ranks > 0) {
    argv = {config_.mpirun};
    // Open MPI refuses to start as root without this; only pass it when it is needed.
    if (geteuid() == 0) argv.push_back("--allow-run-as-root");
    if (!config_.hostfile.empty()) argv.insert(argv.end(), {"--hostfile", config_.hostfile});
    argv.insert(argv.end(), {"--oversubscribe", "-np", std::to_string(config_.ranks)});
  }
  argv.push_back(config_.engine);
  argv.insert(argv.end(), request.engine_args.begin(), request.engine_args.end());
  return argv;
}

std::string LocalExecutor::launch(const LaunchRequest& request) {
  auto args = command(request);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  Fd log{open(request.log_file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644)};
  if (log.fd < 0) throw std::runtime_error("cannot open " + request.log_file.string());

  // posix_spawn rather than fork: the server is multi-threaded, and the child must start clean.
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, log.fd, 1);
  posix_spawn_file_actions_adddup2(&actions, log.fd, 2);
  // Nothing else leaks into the job: above all not the server's listening socket, which an
  // orphaned job would otherwise keep bound after a server crash.
  posix_spawn_file_actions_addclosefrom_np(&actions, 3);
  posix_spawn_file_actions_addchdir_np(&actions, request.job_dir.c_str());

  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  // Own process group (pgid = pid), so cancelling reaches mpirun and every rank.
  posix_spawnattr_setpgroup(&attr, 0);
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  for (int sig : {SIGTERM, SIGINT, SIGHUP, SIGPIPE, SIGQUIT, SIGCHLD}) sigaddset(&defaults, sig);
  posix_spawnattr_setsigmask(&attr, &none);  // the server blocks signals for its signal thread
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setflags(&attr,
                           POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);

  pid_t pid = 0;
  int rc = posix_spawnp(&pid, argv[0], &actions, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (rc != 0) throw std::runtime_error("cannot start " + args[0] + ": " + std::strerror(rc));
  {
    // pids are reused (pid_max may be 32768): an old child's status must not answer for this one.
    std::lock_guard lock(mutex_);
    finished_.erase(pid);
  }
  return std::to_string(pid);
}

ExitStatus LocalExecutor::reap(pid_t pid, bool block) {
  {
    std::lock_guard lock(mutex_);
    auto it = finished_.find(pid);
    if (it != finished_.end()) return it->second;
  }
  int status = 0;
  pid_t r = waitpid(pid, &status, block ? 0 : WNOHANG);
  if (r == 0) return {};
  ExitStatus s;
  if (r == pid) {
    s = from_wait_status(status);
  } else {
    s.finished = true;  // not our child any more (already reaped): treat as gone
  }
  // The leader is gone; make sure no rank or helper it left behind keeps running.
  kill(-pid, SIGKILL);
  std::lock_guard lock(mutex_);
  finished_[pid] = s;
  return s;
}

ExitStatus LocalExecutor::poll(const std::string& handle) {
  return reap(parse_handle(handle), false);
}

ExitStatus LocalExecutor::cancel(const std::string& handle) {
  pid_t pid = parse_handle(handle);
  ExitStatus s = reap(pid, false);
  if (s.finished) return s;
  kill(-pid, SIGTERM);
  auto deadline = std::chrono::steady_clock::now() + config_.grace;
  while (std::chrono::steady_clock::now() < deadline) {
    s = reap(pid, false);
    if (s.finished) return s;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(-pid, SIGKILL);
  return reap(pid, true);
}

bool LocalExecutor::stop_orphan(const std::optional<std::string>& handle,
                                const std::filesystem::path& job_dir) {
  std::string engine_name = std::filesystem::path(config_.engine).filename().string();
  auto search = [&] {
    std::set<pid_t> groups;
    if (handle) groups.insert(parse_handle(*handle));
    // Every run of the job names its job.json on the command line (absolute path).
    for (pid_t g : groups_mentioning((job_dir / "job.json").string())) groups.insert(g);
    bool stopped = false;
    for (pid_t pgid : groups) {
      // The recorded number may since belong to an unrelated group: only stop engine runs.
      if (group_runs_engine(pgid, engine_name)) stopped |= terminate_group(pgid, config_.grace);
    }
    return stopped;
  };
  // A process in the middle of an exec (mpirun starting ranks, env starting a shell) reads as an
  // empty command line, so a search that stops nothing looks once more a moment later.
  if (search()) return true;
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  return search();
}

}  // namespace rockcal::orch
