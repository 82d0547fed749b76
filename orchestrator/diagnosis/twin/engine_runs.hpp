// Runs rockcal-dem jobs as child processes on this machine, a few at a time, through the service's
// LocalExecutor (own process group, no mpirun). The twin's engine: it needs no server or store.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rockcal::diagnosis {

struct EngineRunConfig {
  std::string engine = "rockcal-dem";  // path, or a name looked up in PATH
  int parallel = 2;                    // runs at once
  std::filesystem::path work_dir;      // job-N/{job.json, result.json, curve.csv, log} per run
};

class EngineRunner {
 public:
  explicit EngineRunner(EngineRunConfig config) : config_(std::move(config)) {}
  // Runs every job (full rockcal-dem job JSON) and returns each result.json, in order. Throws
  // std::runtime_error naming the job directory and the end of its log when a run fails (a run
  // that ended without a peak fails: "no peak: ..."); the others are stopped first.
  std::vector<nlohmann::json> run(const std::vector<nlohmann::json>& jobs);
  int runs_started() const { return next_; }

 private:
  EngineRunConfig config_;
  int next_ = 0;  // numbers the job directories across calls
};

}  // namespace rockcal::diagnosis
