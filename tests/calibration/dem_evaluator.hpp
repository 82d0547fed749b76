// An evaluator that runs the real engine: `rockcal-dem run job.json --out DIR` per test, the jobs
// of a batch in parallel, each run reported as one realisation (peak, strength, modulus and its
// quasi-static measure). A stand-in for the orchestrator's pool, for the real-engine tests only (no
// cache, no retries, no MPI launcher).
#pragma once

#include <atomic>
#include <filesystem>
#include <string>

#include "orchestrator/calibration/evaluator.hpp"

namespace rockcal::calibration::testing {

struct DemEvaluator : Evaluator {
  std::string engine;              // path to rockcal-dem
  nlohmann::json job_template;     // the campaign's "job" block
  std::filesystem::path work_dir;  // one subdirectory per job
  int parallel = 2;
  std::atomic<int> jobs_run{0};  // batches may run concurrently (the bayes search keeps two)

  std::vector<EvaluationOutcome> evaluate_batch(
      std::span<const EvaluationRequest> requests) override;
  std::vector<orch::Ensemble> probe_batch(std::span<const ProbeRequest> probes) override;
  void patch_template(const nlohmann::json& patch) override;
};

}  // namespace rockcal::calibration::testing
