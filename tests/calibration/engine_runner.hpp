// A job runner (orchestrator/job_runner.hpp) that runs the real engine: `rockcal-dem run job.json
// --out DIR` per job, `parallel` at a time, each finished run read as the service reads one
// (orch::read_result; a run without a peak is a failed run, "no peak: <reason>"). A stand-in for
// the service's pool for the real-engine tests only (no cache, no retries, no MPI launcher); the
// calibration's RunnerEvaluator on top of it is the evaluator those tests calibrate with.
#pragma once

#include <atomic>
#include <filesystem>
#include <string>

#include "orchestrator/job_runner.hpp"

namespace rockcal::calibration::testing {

struct EngineRunner : orch::JobRunner {
  std::string engine;              // path to rockcal-dem
  std::filesystem::path work_dir;  // one subdirectory per job
  int parallel = 2;
  std::atomic<int> jobs_run{0};  // batches may run concurrently (the bayes search keeps two)

  // Never cancelled: every job runs to its end.
  std::optional<std::vector<orch::Realisation>> run(
      const std::vector<nlohmann::json>& jobs) override;
};

}  // namespace rockcal::calibration::testing
