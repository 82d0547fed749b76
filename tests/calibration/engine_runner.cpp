#include "engine_runner.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <fstream>
#include <mutex>
#include <thread>

#include "db/store.hpp"
#include "orchestrator/job_files.hpp"
#include "orchestrator/realisations.hpp"

extern char** environ;

namespace rockcal::calibration::testing {
namespace {

// Runs one job as a child process (argv, no shell) in `dir` and reads its result.json as the
// service does: a run without a peak fails with db::no_peak_error, as the store records it.
orch::JobOutcome run_one(const std::string& engine, const nlohmann::json& spec, std::int64_t id,
                         const std::filesystem::path& dir) {
  orch::JobOutcome out{id, db::kFailed, false, std::nullopt, std::nullopt};
  std::filesystem::create_directories(dir);
  const std::string spec_path = (dir / "job.json").string();
  std::ofstream(spec_path) << spec.dump();
  const std::string log = (dir / "log.txt").string();
  std::vector<std::string> args = {engine, "run", spec_path, "--out", dir.string()};
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
    out.error = "cannot start " + engine;
    return out;
  }
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    out.error = "rockcal-dem failed (status " + std::to_string(status) + "), see " + log;
    return out;
  }
  db::JobRow job;
  job.id = id;
  job.test = spec.value("test", "");
  try {
    db::ResultRow result = orch::read_result(dir, job);
    if (result.no_peak) {
      out.error = db::no_peak_error(*result.no_peak);
    } else {
      out.state = db::kSucceeded;
      out.result = std::move(result);
    }
  } catch (const std::exception& e) {
    out.error = std::string(e.what()) + ", see " + log;
  }
  return out;
}

}  // namespace

std::optional<std::vector<orch::Realisation>> EngineRunner::run(
    const std::vector<nlohmann::json>& jobs) {
  const int first = jobs_run.fetch_add(int(jobs.size()));
  std::vector<orch::Realisation> runs(jobs.size());
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
        const int id = first + int(i);
        const auto dir = work_dir / ("job" + std::to_string(id));
        runs[i] = orch::realisation(run_one(engine, jobs[i], id + 1, dir), jobs[i]);
      }
    });
  }
  for (std::thread& t : workers) t.join();
  return runs;
}

}  // namespace rockcal::calibration::testing
