// `rockcal serve`: the service process (store + workers + HTTP) until SIGINT/SIGTERM.
#pragma once

#include <string>
#include <vector>

namespace rockcal::api {

struct ServeOptions {
  std::string db = "rockcal.db";
  std::string data_dir;  // default "<db>.d"
  std::string listen = "127.0.0.1:8080";
  int workers = 0;        // 0: cores / ranks
  int ranks_per_job = 1;  // 0: run the engine without mpirun
  std::string token_file;
  bool protect_reads = false;  // reads of /api/ and /metrics need the token too
  std::string engine;          // default: rockcal-dem next to this binary, else PATH
  std::string mpirun = "mpirun";
  int retries = 2;
  double job_timeout_s = 6 * 3600;
  std::size_t max_jobs = 10000;
  std::size_t max_body = 1 << 20;
  std::vector<std::string> allowed_hosts;  // Host values served; empty: from the listen address
  std::size_t max_connections = 512;       // open HTTP connections (one thread each)
  double read_timeout_s = 5;               // one read of a request may wait this long
  double request_timeout_s = 20;           // a whole request must arrive within this
  double keep_alive_timeout_s = 5;         // idle connections are closed after this
  std::string port_file;                   // written with the bound port once listening
  std::string executor = "local";          // local | slurm
  std::string jobs_dir;           // default "<data-dir>/jobs"; slurm: shared with compute nodes
  std::string mpi_hostfile;       // local: mpirun --hostfile, for ranks on several hosts
  std::string partition;          // slurm: sbatch --partition
  std::string account;            // slurm: sbatch --account
  std::string time_limit;         // slurm: sbatch --time
  std::string srun_mpi = "pmix";  // slurm: srun --mpi ("" = the cluster's MpiDefault)
  int max_queued = 64;            // slurm: jobs submitted to Slurm at once
  double slurm_poll_s = 10;       // slurm: seconds between squeue queries
};

int run_serve(const ServeOptions& options, const std::string& argv0);

// The rockcal-dem to run: beside this binary, else in the build tree's engine/, else from PATH.
std::string default_engine(const std::string& argv0);

}  // namespace rockcal::api
