#include "api/server/serve.hpp"

#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

#include "api/server/server.hpp"
#include "orchestrator/all_kinds.hpp"
#include "orchestrator/job_service.hpp"
#include "orchestrator/local_executor.hpp"
#include "orchestrator/slurm/slurm_executor.hpp"

namespace rockcal::api {
namespace fs = std::filesystem;

// rockcal-dem beside this binary (installed layout), or in the build tree's engine/, else PATH.
std::string default_engine(const std::string& argv0) {
  std::error_code ec;
  fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) self = fs::absolute(argv0);
  for (fs::path candidate : {self.parent_path() / "rockcal-dem",
                             self.parent_path().parent_path() / "engine" / "rockcal-dem"}) {
    if (fs::exists(candidate)) return candidate.string();
  }
  return "rockcal-dem";
}

namespace {

std::pair<std::string, int> split_listen(const std::string& listen) {
  auto colon = listen.rfind(':');
  if (colon == std::string::npos) throw std::runtime_error("--listen must be HOST:PORT");
  int port = std::stoi(listen.substr(colon + 1));
  if (port < 0 || port > 65535) throw std::runtime_error("--listen port out of range");
  return {listen.substr(0, colon), port};
}

bool is_loopback(const std::string& host) {
  return host == "127.0.0.1" || host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

}  // namespace

int run_serve(const ServeOptions& o, const std::string& argv0) {
  // Block the stop signals in every thread; one thread waits for them and stops the server.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
  signal(SIGPIPE, SIG_IGN);

  auto [host, port] = split_listen(o.listen);
  int ranks = std::max(0, o.ranks_per_job);
  int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  int workers = o.workers > 0 ? o.workers : std::max(1, cores / std::max(1, ranks));
  const std::string engine = o.engine.empty() ? default_engine(argv0) : o.engine;

  orch::ServiceConfig cfg;
  std::unique_ptr<orch::Executor> executor;
  if (o.executor == "slurm") {
    orch::slurm::SlurmConfig exec;
    exec.engine = fs::absolute(engine).string();  // srun runs it on a compute node
    exec.ranks = std::max(1, ranks);
    exec.partition = o.partition;
    exec.account = o.account;
    exec.time_limit = o.time_limit;
    exec.srun_mpi = o.srun_mpi;
    exec.query_interval =
        std::chrono::milliseconds(static_cast<std::int64_t>(o.slurm_poll_s * 1000));
    // One worker thread watches each job submitted to Slurm; the marker file is read at most
    // once a second per job (it may be on NFS), squeue at most once per query interval.
    workers = o.max_queued;
    cfg.poll_interval = std::min(exec.query_interval, std::chrono::milliseconds(1000));
    executor = std::make_unique<orch::slurm::SlurmExecutor>(exec);
  } else {
    orch::LocalExecutorConfig exec;
    exec.engine = engine;
    exec.ranks = ranks;
    exec.mpirun = o.mpirun;
    exec.hostfile = o.mpi_hostfile;
    executor = std::make_unique<orch::LocalExecutor>(exec);
  }

  cfg.db_path = o.db;
  cfg.data_dir = o.data_dir;
  cfg.jobs_dir = o.jobs_dir;
  cfg.workers = workers;
  cfg.max_attempts = 1 + std::max(0, o.retries);
  cfg.job_timeout = std::chrono::milliseconds(static_cast<std::int64_t>(o.job_timeout_s * 1000));
  cfg.limits.max_jobs_per_campaign = o.max_jobs;

  ServerConfig server_cfg;
  server_cfg.host = host;
  server_cfg.port = port;
  server_cfg.max_body_bytes = o.max_body;
  server_cfg.allowed_hosts = o.allowed_hosts;
  auto ms = [](double s) { return std::chrono::milliseconds(static_cast<std::int64_t>(s * 1000)); };
  server_cfg.connections.max_connections = o.max_connections;
  server_cfg.connections.read_timeout = ms(o.read_timeout_s);
  server_cfg.connections.request_timeout = ms(o.request_timeout_s);
  server_cfg.connections.keep_alive_timeout = ms(o.keep_alive_timeout_s);
  if (!o.token_file.empty()) server_cfg.token = read_token_file(o.token_file);
  if (o.protect_reads && !server_cfg.token)
    throw std::runtime_error("--protect-reads needs --token-file (the token reads must carry)");
  server_cfg.protect_reads = o.protect_reads;
  // Each open connection is a descriptor: raise the soft limit as far as allowed, and say so when
  // it still cannot hold --max-connections (accept() would then wait for descriptors to free up).
  rlimit files{};
  if (getrlimit(RLIMIT_NOFILE, &files) == 0) {
    files.rlim_cur = files.rlim_max;
    setrlimit(RLIMIT_NOFILE, &files);
    getrlimit(RLIMIT_NOFILE, &files);
    if (files.rlim_cur != RLIM_INFINITY && files.rlim_cur < o.max_connections + 256) {
      std::cerr << "rockcal: warning: " << files.rlim_cur
                << " open files allowed (ulimit -n), fewer than --max-connections "
                << o.max_connections << " + 256 for the store and the jobs\n";
    }
  }
  if (!is_loopback(host) && !server_cfg.token) {
    std::cerr << "rockcal: warning: listening on " << host << " without --token-file\n";
  }

  const std::string executor_name = executor->name();
  orch::JobService service(cfg, std::move(executor));
  if (service.recovered_jobs() > 0) {
    std::cerr << "rockcal: re-queued " << service.recovered_jobs() << " jobs left running; stopped "
              << service.stopped_orphans() << " orphaned process groups\n";
  }
  if (service.reattached_jobs() > 0) {
    std::cerr << "rockcal: re-attached to " << service.reattached_jobs() << " jobs still in "
              << executor_name << "\n";
  }
  orch::add_all_kinds(service.kinds());
  ApiServer server(service, workers, server_cfg);
  int bound = server.bind();
  service.start();

  std::thread signal_waiter([&] {
    int sig = 0;
    sigwait(&stop_signals, &sig);
    std::cerr << "rockcal: signal " << sig << ", stopping\n";
    server.stop();
  });
  std::cout << "rockcal: serving on http://" << host << ":" << bound << " (" << executor_name
            << " executor, " << workers << " workers, " << ranks << " ranks per job, engine "
            << engine << ", data " << service.data_dir().string() << ")" << std::endl;
  if (!o.port_file.empty()) {
    // Written atomically so a watcher never reads a half-written number.
    std::ofstream(o.port_file + ".tmp") << bound << "\n";
    fs::rename(o.port_file + ".tmp", o.port_file);
  }
  bool ok = server.listen();
  if (!ok) {
    // listen_after_bind returned without a signal: wake the waiter so it can be joined.
    kill(getpid(), SIGTERM);
  }
  signal_waiter.join();
  service.stop();
  return ok ? 0 : 1;
}

}  // namespace rockcal::api
