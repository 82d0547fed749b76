// rockcal-dem: runs one DEM job (UCT, BTT, triaxial or elastic) described by a JSON spec.
#include <mpi.h>

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include <CLI/CLI.hpp>

#include "engine/job_file.hpp"
#include "engine/run_job.hpp"
#include "engine/spec.hpp"
#include "engine/stop_request.hpp"

namespace {

constexpr int kExitOk = 0, kExitFailure = 1, kExitInvalid = 2, kExitStopped = 3;

extern "C" void on_signal(int) {
  if (rockcal::setup_stages.load() > 0) {  // nothing to keep yet: stop now (async-signal-safe)
    static const char message[] =
        "rockcal-dem: stopped on request (SIGTERM or SIGINT) while setting up the run\n";
    [[maybe_unused]] const ssize_t n = write(STDERR_FILENO, message, sizeof message - 1);
    _exit(kExitStopped);
  }
  rockcal::process_stop_requested.store(true);
}

// Reads and validates a job file. Prints {"error", "field"} and returns nullopt when invalid.
std::optional<rockcal::JobSpec> load_job(const std::string& path, bool report) {
  std::ifstream in(path);
  rockcal::JobFile job;
  if (in) {
    job = rockcal::read_job(in);
  } else {
    const rockcal::SpecError e("(file)", "cannot open " + path);
    job.error = {{"error", e.what()}, {"field", e.field}};
  }
  if (job.spec) return job.spec;
  if (report) {
    std::cout << rockcal::json_text(job.error) << std::endl;
    std::cerr << "rockcal-dem: invalid job: " << job.error["error"].get<std::string>() << std::endl;
  }
  return std::nullopt;
}

// Started by an MPI launcher (mpirun/mpiexec of Open MPI or MPICH, srun)? A plain start runs the
// serial engine without MPI: a singleton MPI_Init costs about 0.3 s, ten times a small job's whole
// time-step loop, and the service and the diagnosis run thousands of such jobs.
bool launched_by_mpi() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE",
                          "SLURM_PROCID", "ROCKCAL_MPI"}) {
    if (std::getenv(var)) return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  const bool mpi = launched_by_mpi();
  if (mpi) MPI_Init(&argc, &argv);
  const MPI_Comm world = mpi ? MPI_COMM_WORLD : MPI_COMM_NULL;
  int rank = 0, ranks = 1;
  if (mpi) {
    MPI_Comm_rank(world, &rank);
    MPI_Comm_size(world, &ranks);
  }

  CLI::App app{"rockcal-dem: bonded-particle DEM runs of rock tests (UCT, BTT, elastic)"};
  app.require_subcommand(1);
  std::string job_path, out_dir = ".";
  auto* validate =
      app.add_subcommand("validate", "check a job spec; print the canonical spec or the error");
  validate->add_option("job", job_path, "job spec (JSON)")->required();
  auto* run = app.add_subcommand("run", "run a job; write result.json, curve.csv, ... into --out");
  run->add_option("job", job_path, "job spec (JSON)")->required();
  run->add_option("--out", out_dir, "output directory (created if missing)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    if (mpi) MPI_Finalize();
    return code == 0 ? 0 : kExitInvalid;
  }

  int code = kExitOk;
  auto spec = load_job(job_path, rank == 0);
  if (!spec) {
    code = kExitInvalid;
  } else if (validate->parsed()) {
    if (rank == 0)
      std::cout << rockcal::json_text({{"valid", true}, {"spec", rockcal::to_json(*spec)}})
                << std::endl;
  } else {
    std::signal(SIGTERM, on_signal);
    std::signal(SIGINT, on_signal);
    try {
      const nlohmann::json result =
          rockcal::run_job(*spec, out_dir, &rockcal::process_stop_requested, rank == 0, world);
      if (rank == 0) std::cout << rockcal::json_text(result) << std::endl;
      if (result["stop_reason"] == "cancelled") code = kExitStopped;
    } catch (const std::exception& e) {
      std::cerr << "rockcal-dem: run failed on rank " << rank << ": " << e.what() << std::endl;
      if (ranks > 1) MPI_Abort(world, kExitFailure);  // the other ranks would wait forever
      code = kExitFailure;
    }
  }
  if (mpi) MPI_Finalize();
  return code;
}
