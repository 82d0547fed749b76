#include "orchestrator/calibration/campaign.hpp"

#include <cmath>
#include <optional>
#include <set>

#include "engine/effects/effect.hpp"
#include "engine/loadtests/brazilian.hpp"
#include "engine/spec.hpp"
#include "orchestrator/calibration/algorithms.hpp"
#include "orchestrator/calibration/lab_case.hpp"
#include "orchestrator/calibration/reach.hpp"
#include "orchestrator/json_fields.hpp"

namespace rockcal::calibration {

Range parse_log_range(const nlohmann::json& v, const std::string& field) {
  if (!v.is_array() || v.size() != 2) throw orch::RequestError(field, "must be [lower, upper]");
  Range r{orch::finite_number(v[0], field + "[0]"), orch::finite_number(v[1], field + "[1]")};
  if (!(r.lo > 0)) throw orch::RequestError(field, "lower bound must be positive (log space)");
  if (!(r.hi > r.lo)) throw orch::RequestError(field, "upper bound must exceed the lower bound");
  return r;
}

namespace {

using nlohmann::json;

TargetValue parse_target(orch::JsonFields& targets, const std::string& test) {
  orch::JsonFields t(targets.require(test), targets.path_of(test));
  auto load = t.positive("peak_load");
  auto strength = t.positive("strength");
  t.reject_unknown();
  if (load && strength)
    throw orch::RequestError(t.path_of("strength"), "give peak_load or strength");
  if (!load && !strength)
    throw orch::RequestError(t.path_of("peak_load"), "is required (or strength)");
  return load ? TargetValue{TargetQuantity::peak_load, *load}
              : TargetValue{TargetQuantity::strength, *strength};
}

Targets parse_targets(orch::JsonFields& root, const JobSpec& model,
                      const Specimen& model_specimen) {
  orch::JsonFields t(root.require("targets"), "targets");
  const std::string units = t.string("units").value_or("model");
  if (units != "model" && units != "lab") {
    throw orch::RequestError("targets.units", "must be \"model\" or \"lab\"");
  }
  const TargetValue uct = parse_target(t, "uct");
  const TargetValue btt = parse_target(t, "btt");
  std::optional<LabCase> lab;
  if (units == "lab") {
    lab = parse_lab_case(t, model_choice_of(model));
  } else if (t.get("lab") || t.get("model_scale")) {
    throw orch::RequestError("targets.units", "must be \"lab\" when lab and model_scale are given");
  }
  ElasticTargets elastic;
  elastic.youngs_modulus_pa = t.positive("youngs_modulus");
  elastic.poisson_ratio = t.number("poisson_ratio");
  if (elastic.poisson_ratio && !(*elastic.poisson_ratio > -1 && *elastic.poisson_ratio < 0.5))
    throw orch::RequestError("targets.poisson_ratio", "must be in (-1, 0.5)");
  t.reject_unknown();
  Targets out = resolve_targets(uct, btt, model_specimen, lab);
  out.elastic = elastic;
  return out;
}

Specimen model_specimen_of(const JobSpec& model) {
  return {model.sample.diameter_m, model.sample.height_m, model.sample.btt_thickness(),
          btt_strength_factor(model.loading)};
}

// The template through the engine's own validation, for both tests; the bond block is the
// search's to set, so it is filled with a placeholder inside the bounds for this check.
JobSpec validate_template(const json& job_template, const Range& fr0, const Range& fs0) {
  if (!job_template.is_object()) throw orch::RequestError("job", "must be a JSON object");
  if (job_template.contains("bond")) {
    throw orch::RequestError("job.bond", "is set by the calibration; leave it out of the template");
  }
  const BondSpec probe{std::sqrt(fr0.lo * fr0.hi), std::sqrt(fs0.lo * fs0.hi)};
  try {
    parse_job_template(job_template, TestKind::btt, probe);
    return parse_job_template(job_template, TestKind::uct, probe);
  } catch (const SpecError& e) {
    throw orch::under("job", e);
  }
}

Strategy parse_strategy(orch::JsonFields& root) {
  const std::string name = root.string("strategy").value_or("auto");
  if (name == "auto") return Strategy::automatic;
  if (name == "ratio_scale") return Strategy::ratio_scale;
  if (name == "direct_2d") return Strategy::direct_2d;
  if (name == "bayes") return Strategy::bayes;
  throw orch::RequestError("strategy", "must be auto, ratio_scale, direct_2d or bayes");
}

std::vector<std::uint64_t> parse_seeds(orch::JsonFields& root) {
  std::vector<std::uint64_t> seeds;
  const json* v = root.get("seeds");
  if (!v) return seeds;
  if (!v->is_array() || v->size() > 16)
    throw orch::RequestError("seeds", "must be a list of at most 16 seeds");
  std::set<std::uint64_t> seen;
  for (std::size_t i = 0; i < v->size(); ++i) {
    const json& s = (*v)[i];
    const std::string field = "seeds[" + std::to_string(i) + "]";
    if (!s.is_number_integer() || (!s.is_number_unsigned() && s.get<std::int64_t>() < 0)) {
      throw orch::RequestError(field, "must be a non-negative integer");
    }
    if (!seen.insert(s.get<std::uint64_t>()).second) throw orch::RequestError(field, "is repeated");
    seeds.push_back(s.get<std::uint64_t>());
  }
  return seeds;
}

void parse_weights(orch::JsonFields& root, CalibrationCampaign& c) {
  const json* v = root.get("weights");
  if (!v) return;
  orch::JsonFields w(*v, "weights");
  c.weight_uct = w.positive("uct").value_or(c.weight_uct);
  c.weight_btt = w.positive("btt").value_or(c.weight_btt);
  w.reject_unknown();
}

// Every evaluation an ensemble of `realisations` packings. The scatter of the best point over
// other seeds is the older way to the same uncertainty; the two together would mix ensemble means
// with single runs, so a campaign asks for one of them.
void parse_realisations(orch::JsonFields& root, const JobSpec& model, CalibrationCampaign& c) {
  const nlohmann::json* value = root.get("realisations");
  c.auto_realisations = value && value->is_string() && *value == "auto";
  if (c.auto_realisations) {
    c.max_realisations = int(
        root.integer("max_realisations", 2, orch::kMaxRealisations).value_or(c.max_realisations));
  } else {
    if (root.get("max_realisations")) {
      throw orch::RequestError("max_realisations", "only with \"realisations\": \"auto\"");
    }
    try {
      c.realisations = orch::realisation_count(value);
    } catch (const std::invalid_argument& e) {
      throw orch::RequestError("realisations", std::string(e.what()) + ", or \"auto\"");
    }
  }
  const int largest =
      c.auto_realisations ? std::max(c.max_realisations, kPilotRealisations) : c.realisations;
  if (auto problem = orch::realisations_problem(largest, c.sample_seed, seed_matters(model))) {
    throw orch::RequestError("realisations", *problem);
  }
  if ((c.auto_realisations || c.realisations > 1) && !c.scatter_seeds.empty()) {
    throw orch::RequestError(
        "realisations",
        "give \"realisations\" (every evaluation an ensemble) or \"seeds\" (the "
        "best point re-run on other packings), not both");
  }
}

// "inference": {"lab_uncertainty": {"uct": 0.05, "btt": 0.05}, "discrepancy": 0, "level": 0.9,
// "unique_width": 1.5, "batch": n}, only beside "strategy": "bayes".
void parse_inference(orch::JsonFields& root, CalibrationCampaign& c) {
  const json* v = root.get("inference");
  if (!v) return;
  if (c.strategy != Strategy::bayes)
    throw orch::RequestError("inference", "only with \"strategy\": \"bayes\"");
  if (!v->is_object()) throw orch::RequestError("inference", "must be an object");
  orch::JsonFields f(*v, "inference");
  InferenceSettings& s = c.inference;
  if (const json* lab = f.get("lab_uncertainty")) {
    if (!lab->is_object())
      throw orch::RequestError("inference.lab_uncertainty", "must be an object");
    orch::JsonFields l(*lab, "inference.lab_uncertainty");
    const std::optional<double> uct = l.positive("uct"), btt = l.positive("btt");
    s.lab_uct = uct.value_or(s.lab_uct);
    s.lab_btt = btt.value_or(s.lab_btt);
    s.lab_uct_stated = uct.has_value();
    s.lab_btt_stated = btt.has_value();
    l.reject_unknown();
    if (s.lab_uct >= 1 || s.lab_btt >= 1)
      throw orch::RequestError("inference.lab_uncertainty", "must be below 1 (a relative sd)");
  }
  if (f.get("discrepancy")) {
    const double d = f.number("discrepancy").value_or(0.0);
    if (!(d >= 0 && d < 1))
      throw orch::RequestError("inference.discrepancy", "must be in [0, 1) (a relative sd)");
    s.discrepancy = d;
  }
  s.level = f.positive("level").value_or(s.level);
  if (s.level < 0.5 || s.level >= 1)
    throw orch::RequestError("inference.level", "must be in [0.5, 1)");
  s.unique_width = f.positive("unique_width").value_or(s.unique_width);
  if (s.unique_width <= 1)
    throw orch::RequestError("inference.unique_width", "must be above 1 (a factor hi/lo)");
  s.batch = int(f.integer("batch", 1, 64).value_or(0));
  f.reject_unknown();
}

}  // namespace

// "fidelity": {"fine": {merge patch of "job"}, "corrections": n (or with bayes "runs": n),
// "strength_scale": s}. The fine
// template is validated for both tests like the job itself; returns its spec, the model the lab
// targets are mapped to (the answer is the fine specimen's).
std::optional<JobSpec> parse_fidelity(orch::JsonFields& root, CalibrationCampaign& c) {
  const nlohmann::json* f = root.get("fidelity");
  if (!f) return std::nullopt;
  if (!f->is_object()) throw orch::RequestError("fidelity", "must be an object");
  orch::JsonFields fields(*f, "fidelity");
  const nlohmann::json& fine = fields.require("fine");
  if (!fine.is_object() || fine.empty())
    throw orch::RequestError("fidelity.fine", "must be a non-empty object (a patch of \"job\")");
  nlohmann::json tmpl = c.job_template;
  tmpl.merge_patch(fine);
  JobSpec spec;
  try {
    spec = validate_template(tmpl, c.fr0_n, c.fs0_n);
  } catch (const orch::RequestError& e) {
    throw orch::RequestError("fidelity.fine", std::string("the fine job: ") + e.what());
  }
  c.fine_patch = fine;
  c.fine_corrections = int(fields.integer("corrections", 1, 20).value_or(c.fine_corrections));
  c.fine_runs = int(fields.integer("runs", 2, 1'000).value_or(c.fine_runs));
  c.fine_strength_scale = fields.positive("strength_scale").value_or(1.0);
  fields.reject_unknown();
  return spec;
}

// "corrections" steps the old driver's Newton corrections, "runs" budgets the bayes fine runs:
// each only with its own strategy.
void check_fidelity_fields(const json& campaign, const CalibrationCampaign& c) {
  const json* f = campaign.contains("fidelity") ? &campaign.at("fidelity") : nullptr;
  if (!f) return;
  const bool bayes = c.strategy == Strategy::bayes;
  if (bayes && f->contains("corrections"))
    throw orch::RequestError("fidelity.corrections",
                             "not with \"strategy\": \"bayes\" (use \"runs\": its fine runs)");
  if (!bayes && f->contains("runs"))
    throw orch::RequestError("fidelity.runs", "only with \"strategy\": \"bayes\"");
}

// "further_targets": [{"name", "test": "uct" | "btt" | "triaxial", "patch": {...},
// "peak_load": N (the targets' units), "uncertainty": relative sd}], only with "strategy": "bayes"
// and one specimen. Each patched template is validated for its test as the job itself is.
void parse_further_targets(orch::JsonFields& root, CalibrationCampaign& c) {
  const json* list = root.get("further_targets");
  if (!list) return;
  if (c.strategy != Strategy::bayes)
    throw orch::RequestError("further_targets", "only with \"strategy\": \"bayes\"");
  if (!c.fine_patch.is_null())
    throw orch::RequestError("further_targets", "not with \"fidelity\" (one specimen)");
  if (!list->is_array() || list->empty() || list->size() > 4)
    throw orch::RequestError("further_targets", "must be an array of 1 to 4 tests");
  for (std::size_t i = 0; i < list->size(); ++i) {
    const std::string path = "further_targets[" + std::to_string(i) + "]";
    if (!(*list)[i].is_object()) throw orch::RequestError(path, "must be an object");
    orch::JsonFields f((*list)[i], path);
    FurtherTarget t;
    const std::string test = f.string("test").value_or("");
    const std::optional<TestKind> kind = test_kind_from_string(test);
    if (!kind || *kind == TestKind::elastic)
      throw orch::RequestError(f.path_of("test"), "must be uct, btt or triaxial");
    t.test = *kind;
    const json& patch = f.require("patch");
    if (!patch.is_object()) throw orch::RequestError(f.path_of("patch"), "must be an object");
    t.patch = patch;
    json tmpl = c.job_template;
    tmpl.merge_patch(patch);
    try {
      const BondSpec probe{std::sqrt(c.fr0_n.lo * c.fr0_n.hi), std::sqrt(c.fs0_n.lo * c.fs0_n.hi)};
      parse_job_template(tmpl, t.test, probe);
    } catch (const SpecError& e) {
      throw orch::under(f.path_of("patch"), e);
    }
    t.value = f.positive("peak_load").value_or(0.0);
    if (!(t.value > 0)) throw orch::RequestError(f.path_of("peak_load"), "is required (N, > 0)");
    t.model_n = c.targets.scaling ? c.targets.scaling->force_to_model(t.value) : t.value;
    t.sd = f.positive("uncertainty").value_or(std::max(c.inference.lab_uct, c.inference.lab_btt));
    if (t.sd >= 1)
      throw orch::RequestError(f.path_of("uncertainty"), "must be below 1 (a relative sd)");
    t.name = f.string("name").value_or(test + " " + patch.dump());
    f.reject_unknown();
    c.further.push_back(std::move(t));
  }
}

// "reach": {"interaction_range": [factor, ...]}: the ranges the calibration may take, in order.
// The template at each range goes through the engine's validation like the job itself.
void parse_reach(orch::JsonFields& root, CalibrationCampaign& c) {
  const json* v = root.get("reach");
  if (!v) return;
  if (!v->is_object()) throw orch::RequestError("reach", "must be an object");
  orch::JsonFields f(*v, "reach");
  const std::string field = f.path_of("interaction_range");
  const json& list = f.require("interaction_range");
  if (!list.is_array() || list.empty() || list.size() > 4)
    throw orch::RequestError(field, "must be an array of 1 to 4 range factors");
  const json* effects = c.job_template.contains("effects") ? &c.job_template["effects"] : nullptr;
  if (effects && effects->is_object() && effects->contains("interaction_range"))
    throw orch::RequestError(
        field, "not with job.effects.interaction_range (give the ranges in one place)");
  if (!c.fine_patch.is_null())
    throw orch::RequestError(field, "not with \"fidelity\" (the ranges are tried on one specimen)");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string at = field + "[" + std::to_string(i) + "]";
    const double factor = orch::finite_number(list[i], at);
    for (double earlier : c.interaction_ranges) {
      if (earlier == factor) throw orch::RequestError(at, "is repeated");
    }
    json tmpl = c.job_template;
    tmpl.merge_patch(interaction_range_patch(factor));
    try {
      validate_template(tmpl, c.fr0_n, c.fs0_n);
    } catch (const orch::RequestError& e) {
      throw orch::RequestError(at, std::string("the job at this range: ") + e.what());
    }
    c.interaction_ranges.push_back(factor);
  }
  f.reject_unknown();
}

CalibrationCampaign parse_calibration_campaign(const json& campaign) {
  orch::JsonFields root(campaign, "");
  CalibrationCampaign c;
  if (root.string("kind").value_or("") != "calibration") {
    throw orch::RequestError("kind", "must be \"calibration\"");
  }
  c.name = root.string("name").value_or("");
  {
    orch::JsonFields bounds(root.require("bounds"), "bounds");
    c.fr0_n = parse_log_range(bounds.require("fr0"), bounds.path_of("fr0"));
    c.fs0_n = parse_log_range(bounds.require("fs0"), bounds.path_of("fs0"));
    bounds.reject_unknown();
  }
  const json& job_template = root.require("job");
  const JobSpec model = validate_template(job_template, c.fr0_n, c.fs0_n);
  c.job_template = job_template;  // copied once the engine has validated it
  c.model_specimen = model_specimen_of(model);
  c.sample_seed = model.sample.seed;
  // Lab targets map to the fine specimen's model when there is one: its loads are the answer.
  const std::optional<JobSpec> fine = parse_fidelity(root, c);
  c.targets = fine ? parse_targets(root, *fine, model_specimen_of(*fine))
                   : parse_targets(root, model, c.model_specimen);
  c.max_evaluations = int(root.integer("max_evaluations", 4, 10'000).value_or(c.max_evaluations));
  c.tolerance = root.positive("tolerance").value_or(c.tolerance);
  if (c.tolerance >= 1.0)
    throw orch::RequestError("tolerance", "must be below 1 (a relative error)");
  parse_weights(root, c);
  c.algorithm = root.string("algorithm").value_or(c.algorithm);
  if (!nlopt_algorithm(c.algorithm)) {
    std::string known;
    for (const auto& n : algorithm_names()) known += (known.empty() ? "" : ", ") + n;
    throw orch::RequestError("algorithm",
                             "unknown algorithm '" + c.algorithm + "' (known: " + known + ")");
  }
  c.strategy = parse_strategy(root);
  parse_inference(root, c);
  check_fidelity_fields(campaign, c);
  parse_further_targets(root, c);
  parse_reach(root, c);
  if (c.targets.elastic.any() && !c.fine_patch.is_null())
    throw orch::RequestError(
        c.targets.elastic.youngs_modulus_pa ? "targets.youngs_modulus" : "targets.poisson_ratio",
        "not with \"fidelity\" (the stiffness stage calibrates one specimen)");
  c.initial_points = int(root.integer("initial_points", 0, 64).value_or(c.initial_points));
  c.random_seed = std::uint64_t(
      root.integer("random_seed", 0, std::numeric_limits<std::int64_t>::max()).value_or(1));
  c.homogeneity_tolerance =
      root.positive("homogeneity_tolerance").value_or(c.homogeneity_tolerance);
  c.scatter_seeds = parse_seeds(root);
  parse_realisations(root, model, c);
  if (c.strategy == Strategy::bayes && (c.auto_realisations || c.realisations > 1))
    throw orch::RequestError("realisations",
                             "not with \"strategy\": \"bayes\" (its design allocates packings)");
  if (c.strategy == Strategy::bayes && !c.scatter_seeds.empty())
    throw orch::RequestError(
        "seeds", "not with \"strategy\": \"bayes\" (every run is on a packing of its own)");
  c.seed_matters = seed_matters(model);
  c.consistency_evaluations =
      int(root.integer("consistency_evaluations", 0, 1'000).value_or(c.consistency_evaluations));
  c.suggest = root.boolean("suggest").value_or(c.suggest);
  if (c.strategy == Strategy::bayes) {
    // The posterior is the answer: no valley trace after the search, its budget is the search's.
    if (root.get("consistency_evaluations"))
      throw orch::RequestError(
          "consistency_evaluations",
          "not with \"strategy\": \"bayes\" (its region is the consistent set)");
    c.consistency_evaluations = 0;
  }
  root.reject_unknown();
  return c;
}

const char* to_string(Strategy strategy) {
  switch (strategy) {
    case Strategy::automatic:
      return "auto";
    case Strategy::ratio_scale:
      return "ratio_scale";
    case Strategy::direct_2d:
      return "direct_2d";
    case Strategy::bayes:
      return "bayes";
  }
  return "?";
}

}  // namespace rockcal::calibration
