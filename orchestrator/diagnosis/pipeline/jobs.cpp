#include "orchestrator/diagnosis/pipeline/jobs.hpp"

#include <cmath>
#include <stdexcept>

#include "engine/effects/effect.hpp"
#include "engine/units.hpp"
#include "orchestrator/job_files.hpp"

namespace rockcal::diagnosis {

using nlohmann::json;

RunPlan plan_runs(const std::vector<Target>& targets) {
  RunPlan plan;
  for (const Target& t : targets) {
    std::size_t i = 0;
    while (i < plan.runs.size() && !(plan.runs[i] == t.conditions)) ++i;
    if (i == plan.runs.size()) plan.runs.push_back(t.conditions);
    plan.run_of.push_back(i);
  }
  return plan;
}

json job_for(const json& job_template, const JobSpec& model, const RunConditions& c,
             const RunRequest& request) {
  const Numerics& n = request.numerics;
  json job = job_template;
  job["test"] = to_string(c.test);
  json& sample = job["sample"];
  sample["diameter"] = c.diameter_m;
  sample["height"] = c.height_m;
  // Only the disc has a thickness; leaving it alone elsewhere keeps equal cylinders equal jobs.
  if (c.test == TestKind::btt) sample["thickness"] = c.thickness_m;
  sample["seed"] = n.seed;
  const Refinement fine{n.resolution};
  sample["radius"] = fine.radius(model.sample.radius_m);
  if (model.material.kr_n_m) job["material"]["kr"] = fine.kr(*model.material.kr_n_m);
  job["bond"] = {{"fr0", fine.strength(request.point.fr0_n)},
                 {"fs0", fine.strength(request.point.fs0_n)}};
  job["loading"]["platen_velocity"] = c.platen_velocity_m_s * n.speed_factor;
  if (c.test == TestKind::triaxial) job["loading"]["confining_pressure"] = c.confining_pressure_pa;
  if (effect_on(request.point)) {
    const EffectDef* effect = find_effect(request.point.effect);
    if (!effect || effect->params.empty()) {
      throw std::invalid_argument("unknown effect '" + request.point.effect + "'");
    }
    job["effects"] = {
        {effect->name,
         {{effect->params[0].name, effect_value_at(*effect, request.point.s, model)}}}};
  }
  JobSpec spec = parse_job(job);
  // An FCC job without seeded effects is one run under every seed: keeping the template's makes the
  // replicate seeds of such a job the same job, run once.
  if (!seed_matters(spec)) spec.sample.seed = model.sample.seed;
  return to_json(spec);
}

std::optional<double> observable_value(const json& result, Observable observable) {
  if (!result.is_object() || orch::no_peak_reason(result)) return std::nullopt;
  const char* key = to_string(observable);
  auto it = result.find(key);
  if (it == result.end() || !it->is_number()) return std::nullopt;
  const double v = it->get<double>();
  if (!std::isfinite(v) || !(v > 0)) return std::nullopt;
  return v;
}

}  // namespace rockcal::diagnosis
