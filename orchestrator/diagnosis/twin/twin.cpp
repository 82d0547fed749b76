#include "orchestrator/diagnosis/twin/twin.hpp"

#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>

#include "engine/effects/effect.hpp"
#include "engine/units.hpp"
#include "orchestrator/json_fields.hpp"
#include "orchestrator/request_error.hpp"

namespace rockcal::diagnosis {
namespace {

using nlohmann::json;

// SplitMix64: a fully specified generator, unlike std::normal_distribution, whose output differs
// between standard libraries.
class Stream {
 public:
  explicit Stream(std::uint64_t seed) : state_(seed) {}
  double uniform() {  // [0, 1)
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  }
  double normal() {                     // Box-Muller, one value per call
    const double u1 = 1.0 - uniform();  // (0, 1]: the log stays finite
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  std::uint64_t state_;
};

TruthBonds draw_from(const JobSpec& model, Stream& stream) {
  const double u1 = stream.uniform() - 0.5;
  const double u2 = stream.uniform() - 0.5;
  const double fr0 = model.bond.fr0_n * std::exp(u1);
  return {fr0, fr0 * (model.bond.fs0_n / model.bond.fr0_n) * std::exp(u2)};
}

// The observable's value in a run's result.json (keys of engine/output.cpp).
double measured(const json& result, const Observation& o) {
  const json v = result.value(to_string(o.observable), json());
  if (!v.is_number() || !(v.get<double>() > 0) || !std::isfinite(v.get<double>())) {
    throw std::runtime_error("observation " + o.id + ": the run reported no " +
                             to_string(o.observable) + " (" + v.dump() + ")");
  }
  return v.get<double>();
}

// The design's job for one observation, as the twin's model runs it: its own packing seed, and
// for a finer-model twin the continuum kept at a smaller radius (radius, K_r and strengths).
json twin_job(const TwinDesign& design, const Observation& o, const TruthBonds& truth,
              const json& effects, const TwinRequest& request) {
  json job = design.job_template;
  job["sample"]["seed"] = design.model.sample.seed + kTwinSeedOffset + request.seed;
  const Refinement fine{request.resolution};
  job["sample"]["radius"] = fine.radius(design.model.sample.radius_m);
  if (design.model.material.kr_n_m) job["material"]["kr"] = fine.kr(*design.model.material.kr_n_m);
  return observation_job(job, o, fine.strength(truth.fr0_n), fine.strength(truth.fs0_n), effects);
}

std::string note(const TwinRequest& r) {
  const std::string n = json(r.noise).dump();
  const std::string made_by = r.resolution == 1.0 ? "the engine itself at the template's resolution"
                                                  : "the engine at " + json(r.resolution).dump() +
                                                        "x the template's resolution (radius / " +
                                                        json(r.resolution).dump() +
                                                        ", K_r and bond strengths scaled)";
  return "Synthetic lab data made by rockcal twin from " + made_by +
         ", with a hidden model "
         "set-up (bond strengths drawn from the seed, possibly one physics effect); model units. "
         "Lab-like noise: each value is the engine's times exp(" +
         n + " N(0,1)); uncertainty = " + n +
         " x value. The truth is in a separate file (*.truth.json).";
}

}  // namespace

Observation parse_next_test(const json& test, const std::string& path) {
  if (!test.is_object()) throw orch::RequestError(path, "must be an object (a report's next test)");
  orch::JsonFields f(test, path);
  // The dataset's own observation, from the report's shape: model units, the platen speed
  // named as the report names it.
  json obs = {{"value", 1.0}, {"uncertainty", 1.0}, {"role", "calibration"}};
  for (const char* key : {"id", "test", "observable"}) {
    if (const json* v = f.get(key)) obs[key] = *v;
  }
  f.get("description");
  if (const json* c = f.get("conditions")) {
    if (!c->is_object()) throw orch::RequestError(f.path_of("conditions"), "must be an object");
    orch::JsonFields cf(*c, f.path_of("conditions"));
    const auto units = cf.string("units");
    if (units != "model") {
      throw orch::RequestError(cf.path_of("units"), "must be \"model\" (a twin is in model units)");
    }
    json& out = obs["conditions"] = json::object();
    for (const char* key : {"diameter", "height", "thickness", "confining_pressure"}) {
      if (const auto x = cf.positive(key)) out[key] = *x;
    }
    if (const auto v = cf.positive("platen_velocity")) out["loading_rate"] = *v;
    cf.reject_unknown();
  }
  f.reject_unknown();
  Observation o = parse_observation(obs, path);
  o.value = o.uncertainty = 0.0;
  return o;
}

std::vector<Observation> twin_observations(const TwinDesign& design, const TwinRequest& request) {
  std::vector<Observation> all = design.observations;
  all.insert(all.end(), request.next_tests.begin(), request.next_tests.end());
  return all;
}

TruthBonds draw_truth_bonds(const JobSpec& model, std::uint64_t seed) {
  Stream stream(seed);
  return draw_from(model, stream);
}

json twin_effects(const TwinRequest& request) {
  if (request.effect == "none") return json::object();
  const EffectDef* effect = find_effect(request.effect);
  if (!effect || effect->params.empty()) {
    throw orch::RequestError("effect", "unknown effect '" + request.effect + "' (known: none, " +
                                           known_effect_names() + ")");
  }
  const EffectParam& p = effect->params[0];
  if (!(request.value >= p.lo && request.value <= p.hi)) {
    throw orch::RequestError("value", "must be in [" + json(p.lo).dump() + ", " +
                                          json(p.hi).dump() + "] (" + effect->name + "." + p.name +
                                          ")");
  }
  return {{effect->name, {{p.name, request.value}}}};
}

void check_twin_value_changes_model(const JobSpec& model, const TwinRequest& request) {
  if (request.effect == "none") return;
  const EffectDef* effect = find_effect(request.effect);
  if (!effect || effect->params.empty() || !effect->params[0].first_change_of) return;
  const EffectParam& p = effect->params[0];
  const double neutral = effect_neutral(p, model), first = p.first_change_of(model);
  const bool short_of_it = neutral <= first ? request.value < first : request.value > first;
  if (short_of_it) {
    throw orch::RequestError("value", effect->name + "." + p.name + " " +
                                          json(request.value).dump() +
                                          " leaves this template's model unchanged (it changes "
                                          "it from " +
                                          json(first).dump() + " on)");
  }
}

void check_twin_request(const TwinRequest& request) {
  twin_effects(request);
  if (!(request.noise > 0) || !std::isfinite(request.noise)) {
    throw orch::RequestError("noise", "must be positive (the uncertainty is noise x value)");
  }
  if (!(request.resolution >= 1.0 && request.resolution <= 3.0)) {
    throw orch::RequestError("resolution", "must be in [1, 3] (1 = the template's own)");
  }
  // A menu test's id (test_menu.hpp) is never one of the design's.
  for (std::size_t i = 0; i < request.next_tests.size(); ++i) {
    const std::string field = "next_tests[" + std::to_string(i) + "].id";
    const std::string& id = request.next_tests[i].id;
    if (!id.starts_with("menu-")) {
      throw orch::RequestError(field,
                               "must be a menu test's id (menu-...), as the report names it");
    }
    for (std::size_t k = 0; k < i; ++k) {
      if (request.next_tests[k].id == id) {
        throw orch::RequestError(
            field, "duplicate id '" + id + "' (also next_tests[" + std::to_string(k) + "])");
      }
    }
  }
}

TruthBonds truth_of(const JobSpec& model, const TwinRequest& request) {
  return draw_truth_bonds(model, request.truth_seed.value_or(request.seed));
}

TwinJobs twin_jobs(const TwinDesign& design, const TwinRequest& request, const TruthBonds& truth) {
  const json effects = twin_effects(request);
  // Observations measured by the same run (the UCT's peak and its modulus) share one job.
  TwinJobs out;
  for (const Observation& o : twin_observations(design, request)) {
    const json job = twin_job(design, o, truth, effects, request);
    std::size_t k = 0;
    while (k < out.jobs.size() && out.jobs[k] != job) ++k;
    if (k == out.jobs.size()) out.jobs.push_back(job);
    out.job_of.push_back(k);
  }
  return out;
}

Twin make_twin(const TwinDesign& design, const TwinRequest& request, const RunJobs& run) {
  check_twin_request(request);
  check_twin_value_changes_model(design.model, request);
  const json effects = twin_effects(request);
  Stream stream(request.seed);
  // u1, u2 are drawn from the seed's stream whatever the truth, so the noise that follows is the
  // same with and without a truth seed.
  const TruthBonds drawn = draw_from(design.model, stream);
  const TruthBonds truth = request.truth_seed ? truth_of(design.model, request) : drawn;
  const auto [jobs, job_of] = twin_jobs(design, request, truth);
  const std::vector<json> results = run(jobs);
  const std::vector<Observation> observations = twin_observations(design, request);

  Twin twin;
  twin.dataset.name = "synthetic twin (seed " + std::to_string(request.seed) + ")";
  twin.dataset.note = note(request);
  twin.dataset.origin =
      request.resolution == 1.0 ? Origin::same_resolution_model : Origin::finer_model;
  twin.dataset.source =
      "rockcal twin, engine " + results.front().value("engine_version", std::string("?"));
  json truth_observations = json::array();
  for (std::size_t i = 0; i < observations.size(); ++i) {
    Observation o = observations[i];
    const json& result = results[job_of[i]];
    const double clean = measured(result, o);
    o.value = clean * std::exp(request.noise * stream.normal());
    o.uncertainty = request.noise * o.value;
    truth_observations.push_back(
        {{"id", o.id}, {"noise_free", clean}, {"value", o.value}, {"job", job_of[i]}});
    twin.dataset.observations.push_back(o);
  }
  const std::string param = effects.empty() ? "" : effects.begin().value().begin().key();
  twin.truth = {
      {"effect", request.effect},
      {"parameter", param},
      {"value", effects.empty() ? json() : json(request.value)},
      {"fr0", truth.fr0_n},
      {"fs0", truth.fs0_n},
      {"seed", request.seed},
      {"truth_seed", request.truth_seed ? json(*request.truth_seed) : json()},
      {"noise", request.noise},
      {"resolution", request.resolution},
      {"design",
       {{"base_ucs", design.base_ucs_pa},
        {"p_low", design.p_low_pa},
        {"p_high", design.p_high_pa},
        {"template_bond", {{"fr0", design.model.bond.fr0_n}, {"fs0", design.model.bond.fs0_n}}}}},
      {"job_template", design.job_template},
      {"observations", truth_observations},
      {"jobs", jobs}};
  // The dataset must parse as any lab dataset would.
  parse_dataset_json(to_json(twin.dataset));
  return twin;
}

std::string truth_file_for(const std::string& dataset_file) {
  std::filesystem::path truth(dataset_file);
  const std::string ext = truth.extension().string();
  if (ext == ".json" || ext == ".csv") truth.replace_extension();
  return truth.string() + ".truth.json";
}

}  // namespace rockcal::diagnosis
