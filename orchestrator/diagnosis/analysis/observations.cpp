#include "orchestrator/diagnosis/analysis/observations.hpp"

#include <algorithm>

namespace rockcal::diagnosis {
namespace {

RunConditions resolve(const Observation& o, const JobSpec& model) {
  const Conditions& c = o.conditions;
  RunConditions r;
  r.test = o.test;
  r.diameter_m = c.diameter_m.value_or(model.sample.diameter_m);
  r.height_m = c.height_m.value_or(model.sample.height_m);
  r.thickness_m = c.thickness_m.value_or(model.sample.thickness_m.value_or(0.5 * r.diameter_m));
  r.confining_pressure_pa = c.confining_pressure_pa;
  r.platen_velocity_m_s = c.loading_rate_m_s.value_or(template_platen_speed(model));
  return r;
}

}  // namespace

std::vector<Target> model_targets(const Dataset& dataset, const JobSpec& model) {
  check_model_scale(dataset, model);
  std::vector<Target> out;
  for (const Observation& o : in_model_units(dataset).observations) {
    Target t;
    t.id = o.id;
    t.observable = o.observable;
    t.role = o.role;
    t.conditions = resolve(o, model);
    t.value = o.value;
    t.sigma = o.uncertainty / o.value;
    out.push_back(std::move(t));
  }
  return out;
}

std::size_t count_role(const std::vector<Target>& targets, Role role) {
  return std::count_if(targets.begin(), targets.end(),
                       [&](const Target& t) { return t.role == role; });
}

}  // namespace rockcal::diagnosis
