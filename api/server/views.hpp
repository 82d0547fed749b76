// JSON and CSV renderings of store rows, as the API returns them.
#pragma once

#include <nlohmann/json.hpp>

#include "db/records.hpp"
#include "orchestrator/campaign_status.hpp"
#include "orchestrator/job_files.hpp"
#include "orchestrator/realisations.hpp"

namespace rockcal::api {

nlohmann::json campaign_json(const db::CampaignRow& c, const orch::CampaignStatus& s);
// With `detail`, the spec and the full result.json are included.
nlohmann::json job_json(const db::JobRow& j, const std::optional<db::ResultRow>& r, bool detail);
// Where a job's files are downloaded: {"curve_csv", "breaks_csv", "vtk": [...]}, each a path of
// the API, present when the run that answered the job (`outputs`: what it left) wrote it.
nlohmann::json job_files_json(const db::JobRow& j, const std::optional<db::ResultRow>& r,
                              const orch::JobOutputs& outputs);
// One row of a results table: fr0, fs0, test, seed, peak_load, strength, youngs_modulus,
// particles, wall_seconds, state, error (and job id, cached).
nlohmann::json result_row_json(const db::JobResultRow& row);
// One test at one point over its realisations: test, fr0, fs0 and the ensemble (orch::to_json).
nlohmann::json point_json(const orch::PointEnsemble& point);
nlohmann::json stored_result_json(const db::ResultRow& r);

std::string results_csv(const std::vector<db::JobResultRow>& rows);

}  // namespace rockcal::api
