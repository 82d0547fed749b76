#include "orchestrator/realisations.hpp"

#include <map>

#include <nlohmann/json.hpp>

namespace rockcal::orch {
namespace {

using nlohmann::json;

Realisation from(std::uint64_t seed, std::int64_t job_id, const std::string& state, bool cached,
                 const std::optional<db::ResultRow>& result,
                 const std::optional<std::string>& error) {
  Realisation r;
  r.seed = seed;
  r.job_id = job_id;
  r.state = state;
  r.cached = cached;
  if (state == db::kSucceeded && result) {
    r.peak_load_n = result->peak_load;
    r.strength_pa = result->strength;
    r.youngs_modulus_pa = result->youngs_modulus;
    r.poisson_ratio = result->poisson_ratio;
    json doc = json::parse(result->result, nullptr, false);
    if (doc.is_object() && doc.contains("loading_rate") && doc["loading_rate"].is_object()) {
      const json& q = doc["loading_rate"].value("quasi_static", json());
      if (q.is_boolean()) r.quasi_static = q.get<bool>();
    }
    if (doc.is_object()) r.result = std::move(doc);
  } else if (state == db::kFailed || state == db::kCancelled) {
    r.error = error.value_or("job " + std::to_string(job_id) + " " + state);
  }
  return r;
}

// The canonical spec without what tells realisations apart (the seed) or changes no result.
std::string ensemble_key(const json& spec) {
  json key = spec;
  key.erase("output");
  if (key.contains("sample") && key["sample"].is_object()) key["sample"].erase("seed");
  return key.dump();
}

std::uint64_t seed_of(const json& spec) {
  if (!spec.is_object()) return 0;
  auto sample = spec.find("sample");
  if (sample == spec.end() || !sample->is_object()) return 0;
  auto seed = sample->find("seed");
  return seed != sample->end() && seed->is_number_unsigned() ? seed->get<std::uint64_t>() : 0;
}

}  // namespace

Realisation realisation(const db::JobRow& job, const std::optional<db::ResultRow>& result) {
  return from(seed_of(json::parse(job.spec, nullptr, false)), job.id, job.state, job.cached, result,
              job.error);
}

Realisation realisation(const JobOutcome& outcome, const json& spec) {
  return from(seed_of(spec), outcome.job_id, outcome.state, outcome.cached, outcome.result,
              outcome.error);
}

std::vector<PointEnsemble> point_ensembles(const std::vector<db::JobResultRow>& rows) {
  std::map<std::string, std::size_t> group_of;
  std::vector<PointEnsemble> points;
  std::vector<std::vector<Realisation>> members;
  for (const db::JobResultRow& row : rows) {
    const json spec = json::parse(row.job.spec, nullptr, false);
    const std::string key = ensemble_key(spec);
    auto [it, fresh] = group_of.emplace(key, points.size());
    if (fresh) {
      points.push_back({row.job.test, row.job.fr0, row.job.fs0, {}});
      members.emplace_back();
    }
    members[it->second].push_back(
        from(seed_of(spec), row.job.id, row.job.state, row.job.cached, row.result, row.job.error));
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i].ensemble = make_ensemble(std::move(members[i]));
  }
  return points;
}

}  // namespace rockcal::orch
