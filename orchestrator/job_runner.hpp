// The one way a campaign runs engine jobs: calibration, diagnosis and twins hand a batch of jobs to
// a JobRunner and read back one Realisation per job. A job is a canonical engine job (parse_job +
// to_json, so equal runs are byte-equal and the job cache knows them); each realisation of an
// ensemble is its own job, its packing seed in sample.seed. What comes back is the run's values
// (peak load, strength, modulus, Poisson's ratio, its quasi-static measure, the whole
// result.json), or why it has none (the failure's reason; a run that ended without a peak is a
// failed run, "no peak: <the engine's reason>"), and whether the job cache answered it. The
// service's worker pool implements it (pool_runner.hpp); a domain turns its requests into jobs and
// the realisations into its outcomes, and holds no submission, waiting or outcome reading of its
// own.
#pragma once

#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "orchestrator/ensemble.hpp"

namespace rockcal::orch {

class JobRunner {
 public:
  virtual ~JobRunner() = default;
  // Runs every job (all at once where the runner can), blocks until all have ended, and returns
  // one realisation per job, in order; std::nullopt when the campaign is cancelled or the server
  // stops (the caller stops rather than read partial results). Running a job again gives the same
  // realisation (the job cache), which is what lets a restarted campaign replay its history.
  virtual std::optional<std::vector<Realisation>> run(const std::vector<nlohmann::json>& jobs) = 0;
};

// Groups of jobs, each the realisations of one test at one model point, run as one batch: one
// ensemble per group, in order; std::nullopt when cancelled.
std::optional<std::vector<Ensemble>> run_ensembles(
    JobRunner& runner, const std::vector<std::vector<nlohmann::json>>& groups);

}  // namespace rockcal::orch
