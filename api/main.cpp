// rockcal: the calibration service (`serve`) and its command-line client, in one binary.
#include <CLI/CLI.hpp>

#include <iostream>

#include "api/cli/backup_cli.hpp"
#include "api/cli/client.hpp"
#include "api/cli/twin_cli.hpp"
#include "api/server/serve.hpp"

int main(int argc, char** argv) {
  using namespace rockcal::api;
  CLI::App app{"rockcal: calibrates bonded-particle DEM models of rock"};
  app.require_subcommand(1);

  ServeOptions serve;
  auto* s = app.add_subcommand("serve", "run the service (HTTP API, store and worker pool)");
  s->add_option("--db", serve.db, "SQLite database file")->capture_default_str();
  s->add_option("--data-dir", serve.data_dir, "job files (default: <db>.d)");
  s->add_option("--listen", serve.listen, "HOST:PORT (port 0: any free port)")
      ->capture_default_str();
  s->add_option("--workers", serve.workers,
                "local: jobs run at once (default: cores / ranks); slurm: see --max-queued");
  s->add_option("--ranks-per-job", serve.ranks_per_job, "MPI ranks per job; 0 runs without mpirun")
      ->capture_default_str()
      ->check(CLI::Range(0, 4096));
  s->add_option("--token-file", serve.token_file, "require this bearer token on mutating routes")
      ->check(CLI::ExistingFile);
  s->add_flag("--protect-reads", serve.protect_reads,
              "require the token on reads of /api/ and /metrics too (/healthz and the dashboard's "
              "files stay open)");
  s->add_option("--engine", serve.engine, "rockcal-dem executable");
  s->add_option("--mpirun", serve.mpirun, "MPI launcher")->capture_default_str();
  s->add_option("--retries", serve.retries, "re-runs of a failed job")->capture_default_str();
  s->add_option("--job-timeout", serve.job_timeout_s, "seconds before a job is stopped")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  s->add_option("--max-jobs", serve.max_jobs, "cap on jobs per campaign")->capture_default_str();
  s->add_option("--max-body", serve.max_body, "cap on request body bytes")->capture_default_str();
  s->add_option("--allowed-hosts", serve.allowed_hosts,
                "Host header values served, NAME or NAME:PORT, comma-separated; * for any "
                "(default: the --listen address's names)")
      ->delimiter(',');
  s->add_option("--max-connections", serve.max_connections, "open HTTP connections; more get 503")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  s->add_option("--read-timeout", serve.read_timeout_s, "seconds one read of a request may wait")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  s->add_option("--request-timeout", serve.request_timeout_s,
                "seconds a whole request (head and body) may take to arrive")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  s->add_option("--keep-alive-timeout", serve.keep_alive_timeout_s,
                "seconds an idle connection is kept open")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  s->add_option("--port-file", serve.port_file, "write the bound port here once listening");
  s->add_option("--executor", serve.executor, "where jobs run: local processes or Slurm jobs")
      ->capture_default_str()
      ->check(CLI::IsMember({"local", "slurm"}));
  s->add_option("--jobs-dir", serve.jobs_dir,
                "job directories (default: <data-dir>/jobs; slurm: shared with compute nodes)");
  s->add_option("--mpi-hostfile", serve.mpi_hostfile, "local: mpirun --hostfile for several hosts")
      ->check(CLI::ExistingFile);
  s->add_option("--partition", serve.partition, "slurm: sbatch --partition");
  s->add_option("--account", serve.account, "slurm: sbatch --account");
  s->add_option("--time-limit", serve.time_limit, "slurm: sbatch --time per job (e.g. 2:00:00)");
  s->add_option("--srun-mpi", serve.srun_mpi, "slurm: srun --mpi plugin (empty: MpiDefault)")
      ->capture_default_str();
  s->add_option("--max-queued", serve.max_queued, "slurm: jobs submitted to Slurm at once")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000));
  s->add_option("--slurm-poll", serve.slurm_poll_s, "slurm: seconds between squeue queries")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  // Every option above can be given in a file instead, as `name = value` (the flag without its
  // dashes) under [serve]: the file and the flags are one list of options (deploy/rockcal.conf).
  // A flag on the command line wins over the file; an unknown key is an error.
  app.set_config("--config", "", "read `rockcal serve` options from this TOML file ([serve])");
  app.allow_config_extras(CLI::config_extras_mode::error);
  s->fallthrough();  // so `rockcal serve --config FILE` works too

  ClientOptions client;
  std::string file;
  std::int64_t id = 0;
  bool csv = false, wait = false, as_json = false;
  auto add_common = [&](CLI::App* sub) {
    sub->add_option("--server", client.server, "server URL (or $ROCKCAL_SERVER)")
        ->envname("ROCKCAL_SERVER")
        ->capture_default_str();
    sub->add_option("--token-file", client.token_file, "bearer token (or $ROCKCAL_TOKEN)");
  };
  auto* submit = app.add_subcommand("submit", "submit a campaign (JSON file, - for stdin)");
  submit->add_option("file", file)->required();
  auto* status = app.add_subcommand("status", "show a campaign's progress");
  status->add_option("id", id)->required();
  status->add_flag("--wait", wait, "redraw until the campaign has finished");
  status->add_flag("--json", as_json, "print the campaign object (and its summary) as JSON");
  auto* results = app.add_subcommand("results", "print a campaign's results");
  results->add_option("id", id)->required();
  results->add_flag("--csv", csv, "CSV instead of a table");
  auto* cancel = app.add_subcommand("cancel", "cancel a campaign");
  cancel->add_option("id", id)->required();
  auto* list = app.add_subcommand("list", "list campaigns");
  std::string html_out;
  auto* diagnose = app.add_subcommand(
      "diagnose", "run a gap diagnosis (request JSON), print the verdict, write the HTML report");
  diagnose->add_option("file", file, "diagnosis request (docs/diagnosis.md)")->required();
  diagnose->add_option("--html", html_out, "HTML report file (default diagnosis-<id>.html)");
  for (auto* sub : {submit, status, results, cancel, list, diagnose}) add_common(sub);

  TwinOptions twin_options;
  auto* twin = app.add_subcommand(
      "twin",
      "write a synthetic lab dataset made by the engine with a hidden effect (+ its truth)");
  twin->add_option("--effect", twin_options.effect, "engine effect, or none")->required();
  auto* value = twin->add_option("--value", twin_options.value, "the effect's fitted parameter");
  twin->add_option("--seed", twin_options.seed, "draws the truth bond strengths and the noise")
      ->capture_default_str();
  twin->add_option("--truth-seed", twin_options.truth_seed,
                   "draws the truth bond strengths instead of --seed (twins of one truth)");
  twin->add_option("--job", twin_options.job, "job template (default: a tiny demo sample)")
      ->check(CLI::ExistingFile);
  twin->add_option("--noise", twin_options.noise, "lognormal sigma of the lab noise")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  twin->add_option("--resolution", twin_options.resolution,
                   "made by a model this many times finer (1 = a same-resolution twin)")
      ->capture_default_str();
  twin->add_option("--engine", twin_options.engine, "rockcal-dem executable");
  twin->add_option("--out", twin_options.out, "dataset file (.json or .csv)")
      ->capture_default_str();
  twin->add_option("--parallel", twin_options.parallel, "engine runs at once")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  twin->add_flag("--keep-runs", twin_options.keep_runs, "keep OUT.runs/ (job dirs and logs)");
  twin->add_option("--next-test", twin_options.next_test,
                   "JSON file: a diagnosis report's next test (or a list), measured too as a "
                   "calibration observation")
      ->check(CLI::ExistingFile);

  std::string backup_db = "rockcal.db", backup_out, restore_from, restore_data_dir;
  auto* backup = app.add_subcommand(
      "backup", "copy the live database (SQLite online backup; the server may be running)");
  backup->add_option("--db", backup_db, "SQLite database file")->capture_default_str();
  backup->add_option("--out", backup_out, "backup file to write")->required();
  auto* restore =
      app.add_subcommand("restore", "replace the database by a backup (server stopped)");
  restore->add_option("--from", restore_from, "backup file")->required()->check(CLI::ExistingFile);
  restore->add_option("--db", backup_db, "SQLite database file")->capture_default_str();
  restore->add_option("--data-dir", restore_data_dir, "the server's data dir (default: <db>.d)");

  CLI11_PARSE(app, argc, argv);
  try {
    if (*s) return run_serve(serve, argv[0]);
    if (*submit) return client_submit(client, file);
    if (*status) return client_status(client, id, wait, as_json);
    if (*results) return client_results(client, id, csv);
    if (*cancel) return client_cancel(client, id);
    if (*list) return client_list(client);
    if (*backup) return run_backup(backup_db, backup_out);
    if (*restore) return run_restore(restore_from, backup_db, restore_data_dir);
    if (*diagnose) return client_diagnose(client, file, html_out);
    if (*twin) {
      twin_options.value_given = value->count() > 0;
      return run_twin(twin_options, argv[0]);
    }
  } catch (const std::exception& e) {
    std::cerr << "rockcal: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
