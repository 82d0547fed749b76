// A campaign's jobs as ensembles: jobs whose canonical specs differ only in sample.seed are the
// realisations of one test at one model point (a sweep's "realisations", a calibration's
// evaluation). What the results API and the pool runner (pool_runner.hpp) read jobs through.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "db/records.hpp"
#include "orchestrator/ensemble.hpp"
#include "orchestrator/job_service.hpp"

namespace rockcal::orch {

// One job as a realisation: its state, its values when it succeeded, else why it has none.
Realisation realisation(const db::JobRow& job, const std::optional<db::ResultRow>& result);
// The same for a job a driver waited for; `spec` is the job it submitted (its sample.seed).
Realisation realisation(const JobOutcome& outcome, const nlohmann::json& spec);

struct PointEnsemble {
  std::string test;
  double fr0 = 0;
  double fs0 = 0;
  Ensemble ensemble;
};

// The campaign's rows grouped into ensembles, in the order of each group's first job.
std::vector<PointEnsemble> point_ensembles(const std::vector<db::JobResultRow>& rows);

}  // namespace rockcal::orch
