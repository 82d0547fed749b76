#include "orchestrator/diagnosis/pipeline/campaign.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "engine/effects/effect.hpp"
#include "orchestrator/diagnosis/pipeline/grid.hpp"
#include "orchestrator/diagnosis/pipeline/jobs.hpp"
#include "orchestrator/json_fields.hpp"

namespace rockcal::diagnosis {
namespace {

using nlohmann::json;

GridSpec parse_grid(orch::JsonFields& root) {
  GridSpec g;
  const json* v = root.get("grid");
  if (!v) return g;
  orch::JsonFields f(*v, "grid");
  if (auto d = f.string("design")) {
    if (*d == "local") {
      g.design = Design::local;
    } else if (*d != "global") {
      throw orch::RequestError(f.path_of("design"), "must be \"global\" or \"local\"");
    }
  }
  if (auto h = f.number("step")) {
    if (!(*h > 0 && *h <= 0.25)) {
      throw orch::RequestError(f.path_of("step"), "must lie in (0, 0.25] (unit-cube half-width)");
    }
    g.step = *h;
  }
  // Three values per axis is the least a quadratic can be fitted to.
  g.fr0 = int(f.integer("fr0", 3, 12).value_or(g.fr0));
  g.fs0 = int(f.integer("fs0", 3, 12).value_or(g.fs0));
  g.s = int(f.integer("s", 3, 9).value_or(g.s));
  f.reject_unknown();
  return g;
}

// "decision": the verdict rule's thresholds, e.g. an evidence threshold calibrated on null twins.
DecisionRule parse_decision(orch::JsonFields& root) {
  DecisionRule rule;
  const json* v = root.get("decision");
  if (!v) return rule;
  orch::JsonFields f(*v, "decision");
  rule.gap_budgets = f.positive("gap_budgets").value_or(rule.gap_budgets);
  if (auto e = f.number("min_evidence")) {
    if (!(*e >= 0)) throw orch::RequestError(f.path_of("min_evidence"), "must be 0 or more (nats)");
    rule.min_evidence = *e;
  }
  f.reject_unknown();
  return rule;
}

// Four packings besides the template's: two under-read a squat UCT's packing scatter (their sd
// 0.02-0.09 in ln where sixteen seeds gave 0.10-0.15 at D/R 20), and the nulls' held-out gaps
// then read as effects (docs/diagnosis-measurements.md, the four-seed matrix).
std::vector<std::uint64_t> default_seeds(std::uint64_t template_seed) {
  return {template_seed + 1, template_seed + 2, template_seed + 3, template_seed + 4};
}

std::vector<std::uint64_t> parse_seeds(orch::JsonFields& f, std::uint64_t template_seed) {
  const json* v = f.get("seeds");
  if (!v) return default_seeds(template_seed);
  const std::string field = f.path_of("seeds");
  if (!v->is_array() || v->size() > 8)
    throw orch::RequestError(field, "must be a list of at most 8");
  std::set<std::uint64_t> seen{template_seed};
  std::vector<std::uint64_t> seeds;
  for (std::size_t i = 0; i < v->size(); ++i) {
    const json& s = (*v)[i];
    const std::string item = field + "[" + std::to_string(i) + "]";
    if (!s.is_number_integer() || (!s.is_number_unsigned() && s.get<std::int64_t>() < 0)) {
      throw orch::RequestError(item, "must be a non-negative integer");
    }
    if (!seen.insert(s.get<std::uint64_t>()).second) {
      throw orch::RequestError(item, "repeats a seed (the template's own seed is the reference)");
    }
    seeds.push_back(s.get<std::uint64_t>());
  }
  return seeds;
}

// A number or a list of up to 4 distinct numbers, each in (1, 3].
std::vector<double> parse_resolutions(orch::JsonFields& f, std::vector<double> fallback) {
  const json* v = f.get("resolution");
  if (!v) return fallback;
  const std::string field = f.path_of("resolution");
  const json list = v->is_array() ? *v : json::array({*v});
  if (list.empty() || list.size() > 4) {
    throw orch::RequestError(field, "must be a number or a list of 1 to 4 numbers");
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string item = v->is_array() ? field + "[" + std::to_string(i) + "]" : field;
    const json& r = list[i];
    if (!r.is_number() || !(r.get<double>() > 1.0 && r.get<double>() <= 3.0)) {
      throw orch::RequestError(item, "must be a number in (1, 3] (a finer packing)");
    }
    if (std::find(out.begin(), out.end(), r.get<double>()) != out.end()) {
      throw orch::RequestError(item, "repeats a resolution");
    }
    out.push_back(r.get<double>());
  }
  return out;
}

BudgetSpec parse_budget(orch::JsonFields& root, std::uint64_t template_seed) {
  BudgetSpec b;
  const json* v = root.get("budget");
  if (!v) {
    b.seeds = default_seeds(template_seed);
    return b;
  }
  orch::JsonFields f(*v, "budget");
  b.seeds = parse_seeds(f, template_seed);
  b.speed_factor = f.positive("speed_factor").value_or(b.speed_factor);
  if (!(b.speed_factor < 1.0)) {
    throw orch::RequestError("budget.speed_factor", "must be below 1 (a slower platen)");
  }
  b.resolutions = parse_resolutions(f, b.resolutions);
  b.points = int(f.integer("points", 1, 9).value_or(b.points));
  f.reject_unknown();
  return b;
}

std::vector<Candidate> parse_effects(orch::JsonFields& root, const JobSpec& model) {
  std::vector<Candidate> all = registry_candidates(model);
  const json* v = root.get("effects");
  if (!v) return all;
  // [] asks for the base model alone: where the gap lies, without ranking effects.
  if (!v->is_array()) {
    throw orch::RequestError(
        "effects", "must be a list of effect names (known: " + known_effect_names() + ")");
  }
  std::vector<Candidate> out;
  std::set<std::string> seen;
  for (std::size_t i = 0; i < v->size(); ++i) {
    const std::string field = "effects[" + std::to_string(i) + "]";
    if (!(*v)[i].is_string()) throw orch::RequestError(field, "must be an effect name");
    const std::string name = (*v)[i].get<std::string>();
    auto it =
        std::find_if(all.begin(), all.end(), [&](const Candidate& c) { return c.effect == name; });
    if (it == all.end()) {
      throw orch::RequestError(
          field, "unknown effect '" + name + "' (known: " + known_effect_names() + ")");
    }
    if (!seen.insert(name).second) throw orch::RequestError(field, "is repeated");
    out.push_back(*it);
  }
  return out;
}

// The template through the engine's validation; the diagnosis sets test, bond and effects.
JobSpec parse_template(orch::JsonFields& root) {
  const json& t = root.require("job");
  if (!t.is_object()) throw orch::RequestError("job", "must be a JSON object");
  for (const char* key : {"bond", "effects"}) {
    if (t.contains(key)) {
      throw orch::RequestError(std::string("job.") + key,
                               "is set by the diagnosis; leave it out of the template");
    }
  }
  JobSpec model;
  try {
    model = parse_job_template(t, TestKind::uct, BondSpec{64.0, 64.0});
  } catch (const SpecError& e) {
    throw orch::under("job", e);
  }
  template_platen_speed(model);
  return model;
}

Dataset parse_dataset(orch::JsonFields& root) {
  const json* inline_json = root.get("dataset");
  const json* csv = root.get("dataset_csv");
  if (root.get("dataset_file")) {
    throw orch::RequestError(
        "dataset_file",
        "the server reads no files: put the dataset inline as \"dataset\" (JSON) "
        "or \"dataset_csv\" (text); `rockcal diagnose` does this for you");
  }
  if (inline_json && csv)
    throw orch::RequestError("dataset_csv", "give dataset or dataset_csv, not both");
  if (!inline_json && !csv) throw orch::RequestError("dataset", "is required (or dataset_csv)");
  const std::string prefix = inline_json ? "dataset" : "dataset_csv";
  try {
    if (inline_json) return parse_dataset_json(*inline_json);
    if (!csv->is_string()) throw orch::RequestError("", "must be the CSV text");
    return parse_dataset_csv(csv->get<std::string>());
  } catch (const orch::RequestError& e) {
    throw orch::under(prefix, e);
  }
}

// Every distinct run with the base model and with each effect at its strong end, and the budget's
// variants, through the engine's validation: a request that would fail only in the middle of the
// diagnosis is refused now, naming what to change.
void validate_runs(const DiagnosisCampaign& c, const JobSpec& model) {
  const RunPlan plan = plan_runs(c.targets);
  const Candidate base;
  const std::vector<double> centre{0.5, 0.5, 1.0};
  auto first_target = [&](std::size_t run) {
    for (std::size_t i = 0; i < plan.run_of.size(); ++i) {
      if (plan.run_of[i] == run) return i;
    }
    return std::size_t(0);
  };
  auto check = [&](const RunRequest& r, const std::string& field, std::size_t run) {
    try {
      job_for(c.job_template, model, plan.runs[run], r);
    } catch (const SpecError& e) {
      throw orch::RequestError(field, "the engine refuses the job of " +
                                          c.targets[first_target(run)].id + ": " + e.what());
    }
  };
  const Numerics numerics{c.sample_seed, 1.0, 1.0};
  for (std::size_t run = 0; run < plan.runs.size(); ++run) {
    check({model_point(c, base, centre), numerics},
          "dataset.observations[" + std::to_string(first_target(run)) + "]", run);
    for (std::size_t k = 0; k < c.candidates.size(); ++k) {
      check({model_point(c, c.candidates[k], centre), numerics},
            "effects[" + std::to_string(k) + "]", run);
    }
    check({model_point(c, base, centre), {c.sample_seed, c.budget.speed_factor, 1.0}},
          "budget.speed_factor", run);
    for (double r : c.budget.resolutions) {
      check({model_point(c, base, centre), {c.sample_seed, 1.0, r}}, "budget.resolution", run);
    }
  }
}

}  // namespace

std::vector<Candidate> registry_candidates(const JobSpec& model) {
  std::vector<Candidate> out;
  for (const EffectDef& def : effect_registry()) {
    if (def.params.empty()) continue;
    const EffectDef* d = &def;  // the registry is static: the pointer outlives every campaign
    const EffectParam& p = def.params[0];
    // An effect that jumps at neutral is explored from a floor; one whose change begins further
    // out for this template (its first_change_of) from there, so that no level of its design is
    // the base model again.
    const double floor =
        p.continuous_at_neutral
            ? 0.0
            : std::max(kDiscontinuousFloor, effect_first_change_fraction(def, model));
    out.push_back(
        {def.name, p.name, p.unit, [d, model](double s) { return effect_value_at(*d, s, model); },
         [d, model](double value) { return effect_same_model_span(*d, value, model); }, floor});
  }
  return out;
}

DiagnosisCampaign parse_diagnosis_campaign(const json& request) {
  orch::JsonFields root(request, "");
  DiagnosisCampaign c;
  if (root.string("kind").value_or("") != "diagnosis") {
    throw orch::RequestError("kind", "must be \"diagnosis\"");
  }
  c.name = root.string("name").value_or("");
  if (c.name.size() > 200) throw orch::RequestError("name", "must be at most 200 characters");
  const JobSpec model = parse_template(root);
  c.job_template = request.at("job");  // a copy of the template the engine has just validated
  c.sample_seed = model.sample.seed;
  if (const json* v = root.get("bounds")) {
    orch::JsonFields bounds(*v, "bounds");
    for (auto [key, range] : {std::pair{"fr0", &c.fr0_n}, std::pair{"fs0", &c.fs0_n}}) {
      if (const json* v = bounds.get(key))
        *range = calibration::parse_log_range(*v, bounds.path_of(key));
    }
    bounds.reject_unknown();
  }
  c.grid = parse_grid(root);
  c.screen = root.boolean("screen").value_or(c.screen);
  c.next_test = root.boolean("next_test").value_or(c.next_test);
  c.budget = parse_budget(root, c.sample_seed);
  c.confirm = int(root.integer("confirm", 1, 16).value_or(c.confirm));
  c.refine = int(root.integer("refine", 0, 5).value_or(c.refine));
  c.bootstrap = int(root.integer("bootstrap", 0, 5000).value_or(c.bootstrap));
  c.decision = parse_decision(root);
  c.random_seed = std::uint64_t(
      root.integer("random_seed", 0, std::numeric_limits<std::int64_t>::max()).value_or(1));
  c.candidates = parse_effects(root, model);
  c.dataset = parse_dataset(root);
  root.reject_unknown();
  try {
    c.targets = model_targets(c.dataset, model);
  } catch (const orch::RequestError& e) {
    throw orch::under("dataset", e);
  }
  // Without held-out observations the effects only get their next test: without it they would
  // have nothing to answer.
  if (!judges_effects(c) && !c.candidates.empty() && !c.next_test) {
    throw orch::RequestError("dataset.observations",
                             "has no held_out observation, so no effect can be judged (a better "
                             "calibration fit proves nothing) and with \"next_test\": false none "
                             "gets the test that would show it; ask for \"next_test\": true, or "
                             "\"effects\": [] to only locate the gap");
  }
  validate_runs(c, model);
  return c;
}

bool judges_effects(const DiagnosisCampaign& c) {
  return count_role(c.targets, Role::held_out) > 0;
}

}  // namespace rockcal::diagnosis
