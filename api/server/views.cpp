#include "api/server/views.hpp"

#include "api/server/http_util.hpp"

namespace rockcal::api {

using nlohmann::json;

namespace {

template <typename T>
json or_null(const std::optional<T>& v) {
  return v ? json(*v) : json(nullptr);
}

json parsed_or_null(const std::optional<std::string>& text) {
  if (!text) return nullptr;
  json j = json::parse(*text, nullptr, false);
  return j.is_discarded() ? json(nullptr) : j;
}

// The packing seed of a job (its realisation), from its canonical spec.
json seed_of(const db::JobRow& j) {
  return orch::realisation(j, std::nullopt).seed;
}

// How a result's strength follows from its peak load, as the engine stated it in result.json
// (engine/loadtests/strength.hpp); null for the elastic test.
json strength_definition_of(const db::ResultRow& r) {
  const json result = json::parse(r.result, nullptr, false);
  return result.is_object() ? result.value("strength_definition", json(nullptr)) : json(nullptr);
}

}  // namespace

json campaign_json(const db::CampaignRow& c, const orch::CampaignStatus& s) {
  json progress = {{"total", s.counts.total()},
                   {"queued", s.counts.queued},
                   {"running", s.counts.running},
                   {"succeeded", s.counts.succeeded},
                   {"failed", s.counts.failed},
                   {"cancelled", s.counts.cancelled},
                   {"cached", s.counts.cached},
                   {"fraction", s.fraction},
                   {"eta_seconds", or_null(s.eta_seconds)}};
  json j = {{"id", c.id},          {"kind", c.kind},
            {"name", c.name},      {"created_at", c.created_at},
            {"state", s.state},    {"cancel_requested", c.cancel_requested},
            {"progress", progress}};
  if (c.driver_status) j["driver_status"] = *c.driver_status;
  if (c.summary) {
    j["summary"] = parsed_or_null(c.summary);
    // A calibration's answer sits at the top level, where clients of the first calibration API look
    // for it.
    if (j["summary"].is_object() && j["summary"].contains("best")) j["best"] = j["summary"]["best"];
    // The running driver's progress model as of now (a diagnosis's jobs done are counted as it is
    // read): every reader finds it where the final report keeps it.
    if (j["summary"].is_object() && !s.model.is_null()) j["summary"]["progress"] = s.model;
  }
  return j;
}

json job_json(const db::JobRow& j, const std::optional<db::ResultRow>& r, bool detail) {
  json out = {{"id", j.id},
              {"campaign_id", j.campaign_id},
              {"test", j.test},
              {"fr0", j.fr0},
              {"fs0", j.fs0},
              {"state", j.state},
              {"cached", j.cached},
              {"attempts", j.attempts},
              {"hash", j.hash},
              {"error", or_null(j.error)},
              {"progress", or_null(j.progress)},
              {"created_at", j.created_at},
              {"started_at", or_null(j.started_at)},
              {"finished_at", or_null(j.finished_at)}};
  if (detail) {
    out["spec"] = parsed_or_null(j.spec);
    out["result"] = r ? parsed_or_null(r->result) : json(nullptr);
  }
  return out;
}

json job_files_json(const db::JobRow& j, const std::optional<db::ResultRow>& r,
                    const orch::JobOutputs& outputs) {
  const std::string base = "/api/v1/jobs/" + std::to_string(j.id);
  json vtk = json::array();
  for (const std::string& name : outputs.vtk) vtk.push_back(base + "/vtk/" + name);
  return {{"curve_csv", r && r->curve ? json(base + "/curve") : json(nullptr)},
          {"breaks_csv", outputs.breaks_csv ? json(base + "/breaks") : json(nullptr)},
          {"vtk", vtk}};
}

json result_row_json(const db::JobResultRow& row) {
  const auto& j = row.job;
  const auto& r = row.result;
  return {{"job_id", j.id},
          {"fr0", j.fr0},
          {"fs0", j.fs0},
          {"test", j.test},
          {"seed", seed_of(j)},
          {"peak_load", r ? or_null(r->peak_load) : json(nullptr)},
          {"strength", r ? or_null(r->strength) : json(nullptr)},
          {"strength_definition", r ? strength_definition_of(*r) : json(nullptr)},
          {"youngs_modulus", r ? or_null(r->youngs_modulus) : json(nullptr)},
          {"particles", r ? or_null(r->particles) : json(nullptr)},
          {"wall_seconds", r ? or_null(r->wall_seconds) : json(nullptr)},
          {"state", j.state},
          {"cached", j.cached},
          {"error", or_null(j.error)}};
}

json point_json(const orch::PointEnsemble& p) {
  json j = {{"test", p.test}, {"fr0", p.fr0}, {"fs0", p.fs0}};
  j.update(orch::to_json(p.ensemble));
  return j;
}

json stored_result_json(const db::ResultRow& r) {
  return {{"job_id", r.job_id},
          {"hash", r.hash},
          {"test", r.test},
          {"fr0", r.fr0},
          {"fs0", r.fs0},
          {"peak_load", or_null(r.peak_load)},
          {"strength", or_null(r.strength)},
          {"strength_definition", strength_definition_of(r)},
          {"youngs_modulus", or_null(r.youngs_modulus)},
          {"poisson_ratio", or_null(r.poisson_ratio)},
          {"particles", or_null(r.particles)},
          {"wall_seconds", or_null(r.wall_seconds)},
          {"engine_version", r.engine_version},
          {"no_peak", or_null(r.no_peak)}};
}

namespace {

// A CSV field that may hold commas or quotes: quoted, its quotes doubled (RFC 4180).
std::string csv_quoted(const std::string& text) {
  std::string out = "\"";
  for (char ch : text) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}

}  // namespace

std::string results_csv(const std::vector<db::JobResultRow>& rows) {
  // Units in the column names; `error` is why a job has no values (its first line).
  std::string out =
      "fr0_n,fs0_n,test,peak_load_n,strength_pa,youngs_modulus_pa,particles,wall_seconds,state,"
      "job_id,seed,error\n";
  auto num = [](const std::optional<double>& v) { return v ? number_text(*v) : std::string(); };
  for (const auto& row : rows) {
    const auto& r = row.result;
    out += number_text(row.job.fr0) + "," + number_text(row.job.fs0) + "," + row.job.test + ",";
    out += (r ? num(r->peak_load) : "") + "," + (r ? num(r->strength) : "") + ",";
    out += (r ? num(r->youngs_modulus) : "") + ",";
    out += (r && r->particles ? std::to_string(*r->particles) : "") + ",";
    out += (r ? num(r->wall_seconds) : "") + "," + row.job.state + "," + std::to_string(row.job.id);
    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "," + std::string.
    out += ',';
    out += seed_of(row.job).dump();
    out += ',';
    if (row.job.error) out += csv_quoted(row.job.error->substr(0, row.job.error->find('\n')));
    out += '\n';
  }
  return out;
}

}  // namespace rockcal::api
