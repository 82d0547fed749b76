#include "dem_evaluator.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <fstream>
#include <mutex>
#include <thread>

extern char** environ;

namespace rockcal::calibration::testing {
namespace {

struct Job {
  nlohmann::json spec;
  std::filesystem::path dir;
  orch::Realisation run;  // what the run reported, as the service's pool reads a job
};

// Runs one job as a child process (argv, no shell) and reads its result.json.
void run(const std::string& engine, Job& job) {
  job.run.seed = job.spec["sample"].value("seed", std::uint64_t{0});
  job.run.state = "failed";
  std::filesystem::create_directories(job.dir);
  const std::string spec_path = (job.dir / "job.json").string();
  std::ofstream(spec_path) << job.spec.dump();
  const std::string out = job.dir.string();
  const std::string log = (job.dir / "log.txt").string();
  std::vector<std::string> args = {engine, "run", spec_path, "--out", out};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, engine.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    job.run.error = "cannot start " + engine;
    return;
  }
  int status = 0;
  waitpid(pid, &status, 0);
  std::ifstream result(job.dir / "result.json");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !result) {
    job.run.error = "rockcal-dem failed (status " + std::to_string(status) + "), see " + log;
    return;
  }
  const nlohmann::json r = nlohmann::json::parse(result);
  // What the run measured, if anything (an elastic test measures E and nu and has no peak).
  if (r.contains("youngs_modulus") && r["youngs_modulus"].is_number())
    job.run.youngs_modulus_pa = r["youngs_modulus"];
  if (r.contains("poisson_ratio") && r["poisson_ratio"].is_number())
    job.run.poisson_ratio = r["poisson_ratio"];
  const bool elastic = job.spec.value("test", "") == "elastic";
  // A compression run without a peak: its largest load is no result (the engine says why).
  if (!elastic && !r.value("peak_reached", true)) {
    job.run.error = "no peak: " + r.value("no_peak_reason", std::string("no peak reached"));
    return;
  }
  job.run.state = "succeeded";
  if (r.contains("peak_load") && r["peak_load"].is_number())
    job.run.peak_load_n = r["peak_load"].get<double>();
  if (r.contains("strength") && r["strength"].is_number()) job.run.strength_pa = r["strength"];
  const nlohmann::json q =
      r.value("loading_rate", nlohmann::json::object()).value("quasi_static", nlohmann::json());
  if (q.is_boolean()) job.run.quasi_static = q.get<bool>();
}

// Runs the jobs `parallel` at a time.
void run_all(const std::string& engine, std::vector<Job>& jobs, int parallel) {
  std::mutex mutex;
  std::size_t next = 0;
  std::vector<std::thread> workers;
  for (int w = 0; w < parallel; ++w) {
    workers.emplace_back([&] {
      for (;;) {
        std::size_t i;
        {
          std::lock_guard lock(mutex);
          if (next == jobs.size()) return;
          i = next++;
        }
        run(engine, jobs[i]);
      }
    });
  }
  for (std::thread& t : workers) t.join();
}

}  // namespace

std::vector<EvaluationOutcome> DemEvaluator::evaluate_batch(
    std::span<const EvaluationRequest> requests) {
  std::vector<Job> jobs;
  int first = jobs_run.fetch_add(2 * int(requests.size()));
  for (const EvaluationRequest& r : requests) {
    for (TestKind test : {TestKind::uct, TestKind::btt}) {
      const std::string name = "job" + std::to_string(first++);
      jobs.push_back({job_for(job_template, r, test, r.sample_seed), work_dir / name, {}});
    }
  }
  run_all(engine, jobs, parallel);
  // One realisation per test, each with its own quasi-static measure, as the pool reports them.
  std::vector<EvaluationOutcome> outcomes;
  for (std::size_t i = 0; i < requests.size(); ++i) {
    outcomes.push_back(outcome_of(orch::make_ensemble({jobs[2 * i].run}),
                                  orch::make_ensemble({jobs[2 * i + 1].run})));
  }
  return outcomes;
}

// Each probe's realisations (seeds sample_seed, sample_seed + 1, ...), with what the runs measured.
std::vector<orch::Ensemble> DemEvaluator::probe_batch(std::span<const ProbeRequest> probes) {
  std::vector<Job> jobs;
  std::vector<std::uint64_t> seeds;
  for (const ProbeRequest& p : probes) {
    for (std::uint64_t seed : orch::realisation_seeds(p.sample_seed, p.realisations)) {
      const std::string name = "job" + std::to_string(jobs_run.fetch_add(1));
      jobs.push_back({job_for(job_template, p, seed), work_dir / name, {}});
      seeds.push_back(seed);
    }
  }
  run_all(engine, jobs, parallel);
  std::vector<orch::Ensemble> out;
  std::size_t next = 0;
  for (const ProbeRequest& p : probes) {
    std::vector<orch::Realisation> runs;
    for (int k = 0; k < p.realisations; ++k, ++next) {
      orch::Realisation x = jobs[next].run;
      x.seed = seeds[next];
      runs.push_back(x);
    }
    out.push_back(orch::make_ensemble(std::move(runs)));
  }
  return out;
}

void DemEvaluator::patch_template(const nlohmann::json& patch) {
  job_template.merge_patch(patch);
}

}  // namespace rockcal::calibration::testing
