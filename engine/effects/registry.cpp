// The list of effects, and what the rest of the engine asks of it. To add an effect: write NAME.cpp
// in this folder defining `EffectDef NAME_effect()` (CMake picks the file up), then declare it and
// add it to the list below: one line each.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/effects/effect.hpp"
#include "engine/spec.hpp"

namespace rockcal {

EffectDef heterogeneity_effect();
EffectDef packing_effect();
EffectDef platen_friction_effect();
EffectDef flaws_effect();
EffectDef rate_effect();
EffectDef compression_coupling_effect();
EffectDef post_break_friction_effect();
EffectDef interaction_range_effect();
EffectDef rolling_resistance_effect();
EffectDef brazilian_flats_effect();

const std::vector<EffectDef>& effect_registry() {
  static const std::vector<EffectDef> all = {
      heterogeneity_effect(),
      packing_effect(),
      platen_friction_effect(),
      flaws_effect(),
      rate_effect(),
      compression_coupling_effect(),
      post_break_friction_effect(),
      interaction_range_effect(),
      rolling_resistance_effect(),
      brazilian_flats_effect(),
  };
  return all;
}

const EffectDef* find_effect(const std::string& name) {
  for (const EffectDef& e : effect_registry())
    if (e.name == name) return &e;
  return nullptr;
}

std::string known_effect_names() {
  std::string out;
  for (const EffectDef& e : effect_registry()) out += (out.empty() ? "" : ", ") + e.name;
  return out;
}

double effect_neutral(const EffectParam& param, const JobSpec& job) {
  return param.neutral_of ? param.neutral_of(job) : param.neutral;
}

namespace {

double value_between(const EffectParam& p, double neutral, double s) {
  s = std::clamp(s, 0.0, 1.0);
  if (s == 0.0) return neutral;
  double x;
  if (std::isinf(neutral))  // no finite "off" value: walk the reciprocal from 0 (off) to 1/strong
    x = p.strong / s;
  else if (p.log_scale)
    x = neutral * std::pow(p.strong / neutral, s);
  else
    x = neutral + s * (p.strong - neutral);
  return std::clamp(x, p.lo, p.hi);
}

}  // namespace

double effect_value_at(const EffectDef& effect, double s) {
  const EffectParam& p = effect.params.at(0);
  return value_between(p, p.neutral, s);
}

double effect_value_at(const EffectDef& effect, double s, const JobSpec& job) {
  const EffectParam& p = effect.params.at(0);
  return value_between(p, effect_neutral(p, job), s);
}

double effect_walk_fraction(const EffectDef& effect, double value, const JobSpec& job) {
  const EffectParam& p = effect.params.at(0);
  const double neutral = effect_neutral(p, job);
  double s;
  if (std::isinf(neutral))
    s = p.strong / value;
  else if (p.log_scale)
    s = std::log(value / neutral) / std::log(p.strong / neutral);
  else
    s = (value - neutral) / (p.strong - neutral);
  return std::clamp(s, 0.0, 1.0);
}

double effect_first_change_fraction(const EffectDef& effect, const JobSpec& job) {
  const EffectParam& p = effect.params.at(0);
  return p.first_change_of ? effect_walk_fraction(effect, p.first_change_of(job), job) : 0.0;
}

ValueSpan effect_same_model_span(const EffectDef& effect, double value, const JobSpec& job) {
  const EffectParam& p = effect.params.at(0);
  return p.same_model_of ? p.same_model_of(job, value) : ValueSpan{value, value};
}

void complete_effects(std::map<std::string, EffectValues>& effects) {
  for (auto& [name, values] : effects) {
    const std::string field = "effects." + name;
    const EffectDef* def = find_effect(name);
    if (!def) throw SpecError(field, "unknown effect (known: " + known_effect_names() + ")");
    for (const auto& entry : values) {
      if (std::none_of(def->params.begin(), def->params.end(),
                       [&](const EffectParam& p) { return p.name == entry.first; }))
        throw SpecError(field + "." + entry.first, "unknown field");
    }
    for (std::size_t k = 0; k < def->params.size(); ++k) {
      const EffectParam& p = def->params[k];
      const double x = values.emplace(p.name, def->defaults.at(k)).first->second;
      if (!(x >= p.lo && x <= p.hi)) {  // also refuses NaN
        const auto fmt = [](double v) { return nlohmann::json(v).dump(); };
        throw SpecError(field + "." + p.name, "must be in [" + fmt(p.lo) + ", " + fmt(p.hi) + "]");
      }
    }
  }
}

JobSpec effective_spec(const JobSpec& job) {
  JobSpec spec = job;
  if (spec.spec_effects_applied) return spec;
  complete_effects(spec.effects);  // specs built in code get the parser's defaults and checks
  for (const EffectDef& e : effect_registry()) {
    const auto it = spec.effects.find(e.name);
    if (it != spec.effects.end() && e.apply_spec) e.apply_spec(spec, it->second);
  }
  spec.spec_effects_applied = true;
  return spec;
}

bool seed_matters(const JobSpec& job) {
  const JobSpec spec = effective_spec(job);
  if (spec.sample.packing != "fcc" || spec.sample.lattice == "seeded") return true;
  for (const EffectDef& e : effect_registry()) {
    if (e.draws_from_seed && spec.effects.count(e.name)) return true;
  }
  return false;
}

void apply_specimen_effects(Simulation& sim, const JobSpec& spec) {
  if (!spec.spec_effects_applied)
    throw std::logic_error("apply_specimen_effects needs the effective spec (effective_spec())");
  for (const EffectDef& e : effect_registry()) {
    const auto it = spec.effects.find(e.name);
    if (it != spec.effects.end() && e.apply_specimen) e.apply_specimen(sim, spec, it->second);
  }
}

}  // namespace rockcal
