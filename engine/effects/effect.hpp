// Optional physics effects for the sim-to-real gap diagnosis. Each effect is one file in this
// folder (a function returning its EffectDef) plus one line in registry.cpp. All are off unless a
// job's "effects" block names them:
//   "effects": {"heterogeneity": {"weibull_m": 4}, "platen_friction": {"mu": 0.3}}
// Effects act once, at set-up (on the parsed spec, or on the built specimen); nothing here runs per
// bond per step, so an effect costs the time-step loop nothing.
//
// A JobSpec keeps the job as written: its fields hold what the job said and `effects` the named
// effects. effective_spec() applies the spec hooks for a run (the parser applies them too, to a
// copy, so that the modified spec is validated); make_specimen() applies the specimen hooks. The
// canonical form (to_json) is therefore the job as written, and parsing it again gives the same
// job: an effect that multiplies a field (rate) is never applied twice.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace rockcal {

struct JobSpec;
struct Simulation;

// Values [from, to) of a parameter; from == to is the one value.
struct ValueSpan {
  double from, to;
};

// One parameter of an effect: its documented range, the value that reproduces the base model (the
// effect "off"), and how the diagnosis walks from off to strong.
struct EffectParam {
  std::string name;
  std::string unit;  // "" when dimensionless
  double lo, hi;     // documented range; values outside are a SpecError
  double neutral;    // the base model's value (may lie outside [lo, hi] for "off" = absent)
  double strong;     // the far end of the range the diagnosis explores
  bool log_scale;    // walk neutral -> strong in log space
  std::string doc;
  // When the base model's value depends on the job (post_break_friction: the job's
  // contact.friction), this gives it; `neutral` then holds the value for the default job.
  double (*neutral_of)(const JobSpec& job) = nullptr;
  // False when no value near `neutral` gives a model near the base one (packing: any radius ratio
  // switches FCC to a random packing). The diagnosis then never interpolates across the jump: it
  // explores such an effect from a floor above neutral and compares it with the base model whole.
  bool continuous_at_neutral = true;
  // For such an effect, when the job decides where its change begins: the least value whose model
  // differs from the base model's for `job`, a little past the jump (interaction_range in an FCC
  // lattice bonds nothing new below the second neighbours' distance, sqrt(2)). The diagnosis then
  // explores the effect from there, not from values that are the base model again.
  double (*first_change_of)(const JobSpec& job) = nullptr;
  // For an effect whose model changes in steps for `job` (interaction_range in a lattice: a shell
  // of neighbours joins at a time), the values around `value` that give the same model as it.
  ValueSpan (*same_model_of)(const JobSpec& job, double value) = nullptr;
};

// Parameter values of one switched-on effect, by name (a job that omits one gets its default).
using EffectValues = std::map<std::string, double>;

struct EffectDef {
  std::string name;
  std::string doc;                  // one paragraph: what it models and what it changes
  std::vector<EffectParam> params;  // at most two; params[0] is the one the diagnosis fits
  std::vector<double> defaults;     // value of each param when a job names the effect but omits it
  // Hooks; either may be empty. apply_spec runs after parsing (it may change the packing, the
  // loading, the contact law ...); apply_specimen runs once the specimen is built and bonded
  // (per-bond strengths, pre-broken bonds, the break rule). Under MPI apply_specimen runs on every
  // rank with its own bonds; it must decide per bond from global ids and the job seed only, so that
  // both ranks holding a border bond agree. Both receive complete values (defaults filled in).
  void (*apply_spec)(JobSpec& spec, const EffectValues& values) = nullptr;
  void (*apply_specimen)(Simulation& sim, const JobSpec& spec,
                         const EffectValues& values) = nullptr;
  bool draws_from_seed = false;  // the job seed draws something (per-bond multipliers, cracks)
};

// Every effect the engine knows, in registration order.
const std::vector<EffectDef>& effect_registry();
const EffectDef* find_effect(const std::string& name);
// "heterogeneity, packing, ..." for error messages.
std::string known_effect_names();

// The value of params[0] at fraction s in [0, 1] of the way from neutral (s = 0) to strong (s = 1),
// linearly or in log space (log_scale). s is clamped to [0, 1]. s = 0 gives the neutral value (the
// effect off: leave it out of the job); for s > 0 the value is clamped into [lo, hi] so that a job
// can carry it. An infinite neutral (heterogeneity's Weibull modulus: no scatter) is walked in
// 1 / value, linearly from 0 to 1 / strong. The first form uses `neutral` as stored (the default
// job's); the second resolves a job-dependent neutral (neutral_of) for `job`.
double effect_value_at(const EffectDef& effect, double s);
double effect_value_at(const EffectDef& effect, double s, const JobSpec& job);
// The base model's value of `param` for `job`.
double effect_neutral(const EffectParam& param, const JobSpec& job);
// The walk fraction s in [0, 1] at which params[0] takes `value` for `job`: effect_value_at's
// inverse inside [lo, hi] (clamped to [0, 1]).
double effect_walk_fraction(const EffectDef& effect, double value, const JobSpec& job);
// The walk fraction where params[0]'s change begins for `job` (its first_change_of), 0 for an
// effect that declares none.
double effect_first_change_fraction(const EffectDef& effect, const JobSpec& job);
// The values of params[0] that give the same model as `value` for `job` (its same_model_of):
// {value, value} for an effect whose model changes with every value.
ValueSpan effect_same_model_span(const EffectDef& effect, double value, const JobSpec& job);

// Fills in every named effect's omitted parameters with their defaults and checks names and ranges.
// Throws SpecError naming the field: "effects.NAME" (unknown effect), "effects.NAME.PARAM"
// (unknown parameter, out of range or NaN).
void complete_effects(std::map<std::string, EffectValues>& effects);

// The spec a run uses: `job` with every named effect's apply_spec applied, in registration order.
// Idempotent: a spec that already is effective (spec_effects_applied) is returned unchanged.
JobSpec effective_spec(const JobSpec& job);

// Whether sample.seed changes anything in this job: a random packing, a seeded FCC lattice, or an
// effect that draws from it. An aligned FCC job without such effects is the same run under every
// seed, so a service need not run it twice.
bool seed_matters(const JobSpec& job);

// Runs every named effect's apply_specimen, in registration order: the one hook point at the end of
// make_specimen (ghosts, local bond indices and the neighbour list exist; dt not yet computed).
void apply_specimen_effects(Simulation& sim, const JobSpec& spec);

}  // namespace rockcal
