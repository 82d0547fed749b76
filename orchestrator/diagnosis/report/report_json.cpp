// to_json of the diagnosis report. JSON has no NaN: quantities that do not exist are null.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "orchestrator/diagnosis/analysis/gap.hpp"
#include "orchestrator/diagnosis/analysis/identifiability.hpp"
#include "orchestrator/diagnosis/analysis/verdict.hpp"
#include "orchestrator/diagnosis/pipeline/grid.hpp"
#include "orchestrator/diagnosis/pipeline/jobs.hpp"
#include "orchestrator/diagnosis/report/next_test_json.hpp"
#include "orchestrator/diagnosis/report/report.hpp"

namespace rockcal::diagnosis {
namespace {

using nlohmann::json;

json num(double x) {
  return std::isfinite(x) ? json(x) : json(nullptr);
}
json num(const std::optional<double>& x) {
  return x ? num(*x) : json(nullptr);
}

json rms_json(const RmsByRole& r) {
  return {{"calibration", num(r.calibration)}, {"held_out", num(r.held_out)}};
}

// Per target, keyed by id: easy to read and to plot.
json by_target(const std::vector<Target>& targets, const std::vector<double>& values) {
  json out = json::object();
  for (std::size_t i = 0; i < targets.size() && i < values.size(); ++i) {
    out[targets[i].id] = num(values[i]);
  }
  return out;
}

json conditions_json(const RunConditions& c) {
  json j = {{"diameter", c.diameter_m}, {"platen_velocity", c.platen_velocity_m_s}};
  if (c.test == TestKind::btt) {
    j["thickness"] = c.thickness_m;
  } else {
    j["height"] = c.height_m;
  }
  if (is_triaxial(c.test)) j["confining_pressure"] = c.confining_pressure_pa;
  return j;
}

json parameter_json(const CandidateResult& c) {
  if (c.candidate.is_base()) return nullptr;
  json j = {{"name", c.candidate.param},
            {"unit", c.candidate.unit},
            {"value", num(c.value)},
            {"s", c.point.s}};
  // A value that stands for a span of them (a lattice's shell of neighbours) says so.
  if (c.candidate.same_model && std::isfinite(c.value)) {
    const ValueSpan span = c.candidate.same_model(c.value);
    if (span.from < span.to) j["same_model"] = {{"from", span.from}, {"to", span.to}};
  }
  return j;
}

// The held-out log predictive density (evidence.hpp), term by term, and an effect's evidence
// over the base model.
json evidence_json(const CandidateResult& c, const std::vector<Target>& targets) {
  if (!c.density) return nullptr;
  json terms = json::array();
  for (const DensityTerm& t : c.density->terms) {
    terms.push_back({{"id", targets[t.target].id},
                     {"charged", t.residual},
                     {"variance", t.variance},
                     {"prediction_variance", t.prediction_variance},
                     {"lpd", t.lpd}});
  }
  return {{"value", num(c.evidence)},
          {"lpd", c.density->lpd},
          {"basis", c.confirmed ? "confirmed" : "surface"},
          {"terms", terms}};
}

json candidate_json(const CandidateResult& c, const std::vector<Target>& targets,
                    const std::vector<double>& lab) {
  json j = {{"effect", c.candidate.is_base() ? json(nullptr) : json(c.candidate.effect)},
            {"rank", c.rank},
            {"fitted", c.fitted},
            {"confirmed", c.confirmed}};
  if (!c.error.empty()) j["error"] = c.error;
  std::vector<double> fit_rms;
  for (const auto& s : c.surfaces.per_target) fit_rms.push_back(s ? s->rms : NAN);
  j["surface_loo_rms"] = by_target(targets, fit_rms);
  if (!c.fitted) return j;
  j["parameter"] = parameter_json(c);
  j["fit"] = {{"fr0", c.point.fr0_n},
              {"fs0", c.point.fs0_n},
              {"misfit", num(c.calibration.misfit)},
              {"evaluations", c.calibration.evaluations},
              {"on_bounds", json(on_bounds(c.calibration.z))}};
  j["rms"] = {{"surface", rms_json(c.surface_rms)},
              {"confirmed", c.confirmed ? rms_json(c.confirmed_rms) : json(nullptr)}};
  j["predicted_residuals"] = by_target(targets, residuals(c.predicted, lab));
  if (c.confirmed) j["residuals"] = by_target(targets, residuals(c.confirmed_ln, lab));
  j["evidence"] = evidence_json(c, targets);
  if (!c.candidate.is_base()) {
    j["gap_closure"] = {{"surface", num(c.g_surface)},
                        {"confirmed", num(c.g_confirmed)},
                        {"value", num(c.g())},
                        {"basis", c.confirmed ? "confirmed" : "surface"}};
    // In noise units, against the base model at the same strengths (confirmed effects only).
    j["mark_at_fit"] = {{"in_noise", num(c.mark_at_fit)}, {"inert", c.inert_at_fit()}};
    const Identifiability& id = *c.identifiability;
    json moved = json::array();
    for (std::size_t i : id.moved) moved.push_back(targets[i].id);
    j["identifiable"] = id.identifiable;
    j["identifiable_reason"] = identifiability_reason(id, targets);
    j["fits_calibration"] = c.fits_calibration;
    j["moves"] = moved;
    j["max_change"] = by_target(targets, id.max_change);
  }
  if (c.confirmed) {
    json steps = json::array();
    for (const RefineStep& step : c.refinement) {
      json p = {{"fr0", step.point.fr0_n}, {"fs0", step.point.fs0_n}, {"misfit", num(step.misfit)}};
      if (!c.candidate.is_base()) {
        p["value"] = num(c.candidate.value_at ? c.candidate.value_at(step.point.s) : step.point.s);
      }
      steps.push_back(std::move(p));
    }
    j["refinement"] = std::move(steps);
  }
  // The winning start's best misfit after each evaluation: the calibration history.
  j["history"] = c.calibration.history;
  return j;
}

// A charged residual beyond budget + lab uncertainty + the fit's spread (sd) is a gap, not noise.
bool significant(double charged, const Target& t, double budget, double fit_variance) {
  return std::isfinite(charged) &&
         std::abs(charged) > budget + t.sigma + std::sqrt(std::max(fit_variance, 0.0));
}

// `spread[k]`: the fit's spread in each prediction of candidate k's runs (held_out_fit_variance),
// for the base and the verdict's model.
json observation_json(std::size_t i, const DiagnosisResult& r, const std::vector<Target>& targets,
                      const std::vector<double>& lab,
                      const std::vector<std::vector<double>>& spread) {
  const Target& t = targets[i];
  const double budget = r.budget.per_target[i];
  json j = {{"id", t.id},
            {"test", to_string(t.conditions.test)},
            {"observable", to_string(t.observable)},
            {"role", to_string(t.role)},
            {"conditions", conditions_json(t.conditions)},
            {"lab", t.value},
            {"lab_uncertainty", t.sigma},
            {"budget", budget},
            {"budget_measured", bool(r.budget.measured[i])},
            {"base_grid_failures", i < r.base_grid_failures.size() ? r.base_grid_failures[i] : 0}};
  auto sim = [&](int k) {
    const CandidateResult& c = r.candidates[k];
    const double res = c.ln_sim()[i] - lab[i];
    // The part the model is charged with: the residual less the span of values the data
    // themselves give under the same conditions (consistency.hpp); the residual elsewhere.
    const double charged = charged_residuals(residuals(c.ln_sim(), lab), targets)[i];
    return json{{"sim", num(std::exp(c.ln_sim()[i]))},
                {"residual", num(res)},
                {"charged", num(charged)},
                // The sd the calibration leaves in this prediction (0 on a calibration one).
                {"fit_spread", std::sqrt(std::max(spread[k][i], 0.0))},
                {"significant", significant(charged, t, budget, spread[k][i])}};
  };
  j["base"] = sim(0);
  j["verdict"] = r.verdict.candidate >= 0 ? sim(r.verdict.candidate) : json(nullptr);
  return j;
}

json confidence_json(const Confidence& c) {
  json winners = json::object();
  for (const auto& [name, n] : c.winners) winners[name.empty() ? "no effect needed" : name] = n;
  json seeds = json::array();
  for (const SeedCheck& s : c.seeds) {
    seeds.push_back({{"seed", s.seed},
                     {"verdict", s.verdict.empty() ? "no effect needed" : s.verdict},
                     {"gap_closure", s.gap_closure},
                     {"evidence", s.evidence},
                     {"informative", s.informative}});
  }
  return {{"level", c.level},
          {"bootstrap",
           {{"replicates", c.replicates},
            {"agreement", c.replicates > 0 ? json(c.agreement) : json(nullptr)},
            {"winners", winners}}},
          {"seeds", seeds},
          {"seeds_informative", c.seeds_informative},
          {"seeds_identical", int(c.seeds.size()) - c.seeds_informative},
          {"seeds_agreeing", c.seeds_agreeing},
          {"method",
           "bootstrap: each replicate redraws every lab value with its lab uncertainty and "
           "numerical budget, re-fits every candidate on its surfaces (anchored to its real runs) "
           "and replays the verdict rule; seeds: the base and confirmed effects re-run at their "
           "fitted points on each replicate packing seed, verdict rule replayed; a seed whose runs "
           "all equal the nominal ones (a regular packing with no seeded effect) tests nothing "
           "and is not counted. high: >= 90% of replicates and every counted seed agree; medium: "
           ">= 70% and most counted seeds; low otherwise"}};
}

// The miss the verdict's reason states, figure by figure.
json miss_json(const std::optional<ModelMiss>& m) {
  if (!m) return nullptr;
  json beyond = json::array();
  for (const ObservationMiss& o : m->beyond) {
    beyond.push_back({{"id", o.id},
                      {"role", to_string(o.role)},
                      {"charged", o.residual},
                      {"fit_spread", o.fit},
                      {"noise", o.noise()},
                      {"budgets", o.in_budgets()}});
  }
  return {{"model", m->model},
          {"rms_budgets", {{"calibration", num(m->calibration)}, {"held_out", num(m->held_out)}}},
          {"beyond", beyond}};
}

json verdict_json(const DiagnosisResult& r, const DecisionRule& rule) {
  const CandidateResult& base = r.candidates[0];
  const int v = r.verdict.candidate;
  json j = {{"effect", v >= 0 ? json(r.candidates[v].candidate.effect) : json(nullptr)},
            {"label", verdict_label(r.candidates, r.verdict)},
            {"undetermined", r.verdict.undetermined},
            {"reason", r.verdict.reason}};
  const CandidateResult& after = v >= 0 ? r.candidates[v] : base;
  j["parameter"] = parameter_json(after);
  j["fr0"] = after.point.fr0_n;
  j["fs0"] = after.point.fs0_n;
  j["gap_closure"] = v >= 0 ? num(after.g_confirmed) : json(nullptr);
  j["gap_closure_beyond_noise"] = num(r.gap_closure_beyond_noise);
  // The contender with the most evidence (named or not) against the rule's threshold.
  const int best = r.verdict.best;
  j["evidence"] = {
      {"effect", best >= 0 ? json(r.candidates[best].candidate.effect) : json(nullptr)},
      {"value", best >= 0 ? num(r.candidates[best].evidence) : json(nullptr)},
      {"threshold", rule.min_evidence},
      {"unit", "nats"}};
  j["gap"] = {{"calibration",
               {{"before", num(base.confirmed_rms.calibration)},
                {"after", num(after.confirmed_rms.calibration)}}},
              {"held_out",
               {{"before", num(base.confirmed_rms.held_out)},
                {"after", num(after.confirmed_rms.held_out)}}}};
  if (r.verdict.runner_up >= 0) {
    const CandidateResult& u = r.candidates[r.verdict.runner_up];
    j["runner_up"] = {{"effect", u.candidate.effect},
                      {"parameter", u.fitted ? parameter_json(u) : json(nullptr)},
                      {"gap_closure", num(u.g())},
                      {"evidence", num(u.evidence)},
                      {"basis", u.confirmed ? "confirmed" : "surface"},
                      {"identifiable", u.identifiability && u.identifiability->identifiable}};
  } else {
    j["runner_up"] = nullptr;
  }
  j["confidence"] = confidence_json(r.confidence);
  j["miss"] = miss_json(r.verdict.miss);
  if (const auto& b = r.verdict.bound) {
    j["bound"] = {{"on_bounds", b->on},
                  {"calibration_budgets", num(b->calibration)},
                  {"refitted_calibration_budgets", num(b->refitted)},
                  {"holds", b->holds}};
  } else {
    j["bound"] = nullptr;
  }
  return j;
}

json budget_json(const DiagnosisResult& r, const std::vector<Target>& targets, Origin origin) {
  json variants = json::array();
  for (std::size_t v = 0; v < r.budget.variants.size(); ++v) {
    const BudgetVariant& b = r.budget.variants[v];
    variants.push_back({{"name", b.name},
                        {"seed", b.numerics.seed},
                        {"speed_factor", b.numerics.speed_factor},
                        {"resolution", b.numerics.resolution},
                        {"refitted", bool(r.budget.refitted[v])},
                        {"change", by_target(targets, r.budget.change[v])}});
  }
  json terms = json::array();
  for (const ErrorTerm& t : error_terms(origin)) {
    terms.push_back({{"kind", t.kind}, {"applies", t.applies}, {"why", t.why}});
  }
  return {
      {"point", {{"fr0", r.budget_point.fr0_n}, {"fs0", r.budget_point.fs0_n}}},
      {"points", r.budget.points},
      {"error_model", {{"origin", to_string(origin)}, {"terms", terms}}},
      {"per_observation", by_target(targets, r.budget.per_target)},
      // The calibrations' weights: the budget at the base model's first fit.
      {"weights",
       {{"point", {{"fr0", r.weight_budget_point.fr0_n}, {"fs0", r.weight_budget_point.fs0_n}}},
        {"per_observation", by_target(targets, r.weight_budget.per_target)}}},
      {"combined", {{"calibration", r.combined_calibration}, {"held_out", r.combined_held_out}}},
      {"variants", variants}};
}

// Why no effect has a gap closure G (null when one has): a chart of G left empty says so.
json closure_missing(const DiagnosisResult& r, const DiagnosisCampaign& campaign) {
  const auto& c = r.candidates;
  const std::string untried =
      campaign.candidates.empty()
          ? "no candidate effects were tried (the request's \"effects\" is empty)"
          : "the screen found every candidate effect invisible to these tests (screen.reason)";
  if (!judges_effects(campaign)) {
    return "G is measured on held-out observations, and the dataset has none; " +
           (campaign.candidates.empty()
                ? untried
                : "so no effect was designed (next_test names the test that would show each)");
  }
  if (c.size() < 2) return untried + ": the diagnosis only locates the gap";
  for (std::size_t k = 1; k < c.size(); ++k) {
    if (c[k].g()) return nullptr;
  }
  if (!c[0].confirmed_rms.held_out) {
    return "the base model has no held-out residual (its runs failed), so no G can be measured";
  }
  if (*c[0].confirmed_rms.held_out == 0) {
    return "the base model meets every held-out observation exactly: there is no gap to close";
  }
  for (std::size_t k = 1; k < c.size(); ++k) {
    if (c[k].fitted) {
      return "no effect's held-out residuals could be compared with the base model's (their "
             "held-out surfaces or runs are missing: runs.failed_values)";
    }
  }
  return "no candidate effect could be fitted (candidates[].error says why)";
}

// `spread`: the fit's spread in each of the base model's predictions (held_out_fit_variance).
json gap_json(const DiagnosisResult& r, const DiagnosisCampaign& c, const std::vector<double>& lab,
              const std::vector<double>& spread) {
  const std::vector<Target>& targets = c.targets;
  const DecisionRule& rule = c.decision;
  const CandidateResult& base = r.candidates[0];
  const std::vector<double> res = charged_residuals(residuals(base.confirmed_ln, lab), targets);
  json beyond_noise = json::array();
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (significant(res[i], targets[i], r.budget.per_target[i], spread[i])) {
      beyond_noise.push_back(targets[i].id);
    }
  }
  return {{"rms", rms_json(base.confirmed_rms)},
          {"combined_budget",
           {{"calibration", r.combined_calibration}, {"held_out", r.combined_held_out}}},
          {"held_out_budgets", num(r.held_out_budgets)},
          {"threshold_budgets", rule.gap_budgets},
          {"exceeds_budget", r.held_out_budgets.value_or(0) > rule.gap_budgets},
          {"significant", beyond_noise},
          {"closure_missing", closure_missing(r, c)}};
}

json ratio_json(const std::optional<LabRatio>& r, const std::vector<Target>& targets) {
  if (!r) return nullptr;
  return {{"uct", targets[r->uct].id}, {"btt", targets[r->btt].id},
          {"lab", r->range.target},    {"min", r->range.min},
          {"max", r->range.max},       {"inside", r->range.target_inside()},
          {"runs", r->range.runs}};
}

}  // namespace

namespace {

json inconsistencies_json(const std::vector<Inconsistency>& pairs,
                          const std::vector<Target>& targets) {
  json out = json::array();
  for (const Inconsistency& p : pairs) {
    out.push_back({{"first", targets[p.first].id},
                   {"second", targets[p.second].id},
                   {"ln_difference", p.ln_difference},
                   {"sigmas", p.sigmas}});
  }
  return out;
}

// The screen's effects and the sentence the report prints, from these fields.
json screen_json(const ScreenResult& screen, const DiagnosisCampaign& c) {
  json effects = json::array(), invisible = json::array();
  std::string named, second;
  char line[256];
  for (const ScreenedEffect& e : screen.effects) {
    json largest = nullptr;
    if (e.largest) {
      const std::size_t i = *e.largest;
      largest = {{"id", c.targets[i].id},
                 {"change", e.change[i]},
                 {"noise", e.noise[i]},
                 {"in_noise", e.largest_in_noise}};
    }
    // The strengths the linear re-fit gives the effect at s = 1 (where its design is centred).
    const ModelPoint refitted =
        model_point(c, Candidate{},
                    std::vector<double>{std::clamp(screen.z[0] + e.fit_shift[0], 0.0, 1.0),
                                        std::clamp(screen.z[1] + e.fit_shift[1], 0.0, 1.0)});
    effects.push_back(
        {{"effect", e.effect},
         {"visible", e.visible},
         {"largest", largest},
         {"change", by_target(c.targets, e.change)},
         {"judged_at", e.at_balanced ? "balanced point" : "base fit"},
         {"refitted_strengths", {{"fr0_n", refitted.fr0_n}, {"fs0_n", refitted.fs0_n}}}});
    if (e.at_balanced) second += (second.empty() ? "" : ", ") + e.effect;
    if (e.visible) continue;
    invisible.push_back(e.effect);
    std::snprintf(line, sizeof line,
                  " (its largest change %.2f of its noise, on %s: %+.3f in ln, noise %.3f)",
                  e.largest_in_noise, c.targets[*e.largest].id.c_str(), e.change[*e.largest],
                  e.noise[*e.largest]);
    named += (named.empty() ? "" : ", ") + e.effect + line;
  }
  // Where the screen looked: "at the base fit (F_r0 256 N, F_s0 27.9 N) and at the balanced point
  // (F_r0 84.4 N, F_s0 84.4 N: equal strengths at their geometric mean, within the box)".
  std::snprintf(line, sizeof line, "at the base fit (F_r0 %.3g N, F_s0 %.3g N)", screen.point.fr0_n,
                screen.point.fs0_n);
  std::string where = line;
  if (!screen.balanced_z.empty()) {
    std::snprintf(line, sizeof line,
                  " and at the balanced point (F_r0 %.3g N, F_s0 %.3g N: equal strengths at their "
                  "geometric mean, within the box)",
                  screen.balanced_point.fr0_n, screen.balanced_point.fs0_n);
    where += line;
  }
  std::string reason;
  if (!screen.enabled) {
    reason = c.screen ? "no candidate effect to screen" : "not screened (\"screen\": false)";
  } else if (named.empty()) {
    reason =
        "every effect moves some observation beyond its noise (budget + lab uncertainty) at "
        "its strong value (s = 1) with the strengths re-fitted, " +
        where + ": none screened out";
  } else {
    reason = "invisible to these tests: " + named +
             ": at its strong value (s = 1), with the strengths re-fitted, each moves no "
             "observation beyond its noise (budget + lab uncertainty) " +
             where;
    if (judges_effects(c)) {
      reason += ", so it was not designed further (" + std::to_string(screen.skipped_model_points) +
                " model points of surfaces not run)";
    }
  }
  if (!second.empty()) {
    reason += "; " + second +
              ": no mark at the base fit but one at the balanced point, so designed around its fit "
              "from there";
  }
  if (screen.enabled && !judges_effects(c)) {
    reason +=
        "; with nothing held out no effect is designed (next_test names the test that "
        "would show each)";
  }
  return {{"enabled", screen.enabled},
          {"point", screen.enabled ? json{{"fr0", screen.point.fr0_n}, {"fs0", screen.point.fs0_n}}
                                   : json(nullptr)},
          {"balanced_point",
           screen.balanced_z.empty()
               ? json(nullptr)
               : json{{"fr0", screen.balanced_point.fr0_n}, {"fs0", screen.balanced_point.fs0_n}}},
          {"model_points", screen.model_points},
          {"skipped_model_points", screen.skipped_model_points},
          {"invisible", invisible},
          {"effects", effects},
          {"reason", reason}};
}

}  // namespace

json to_json(const DiagnosisResult& r, const DiagnosisCampaign& c) {
  const std::vector<double> lab = ln_lab(c.targets);
  std::vector<std::vector<double>> spread(r.candidates.size());
  for (int k : {0, r.verdict.candidate}) {
    if (k >= 0) spread[k] = held_out_fit_variance(r.candidates[k], c.targets, r.budget.per_target);
  }
  json observations = json::array();
  for (std::size_t i = 0; i < c.targets.size(); ++i) {
    observations.push_back(observation_json(i, r, c.targets, lab, spread));
  }
  json candidates = json::array();
  for (const CandidateResult& k : r.candidates)
    candidates.push_back(candidate_json(k, c.targets, lab));
  return {{"kind", "diagnosis"},
          {"name", c.name},
          {"dataset", c.dataset.name},
          {"verdict", verdict_json(r, c.decision)},
          {"gap", gap_json(r, c, lab, spread[0])},
          {"decision",
           {{"gap_budgets", c.decision.gap_budgets}, {"min_evidence", c.decision.min_evidence}}},
          {"observations", observations},
          {"budget", budget_json(r, c.targets, c.dataset.origin)},
          {"ratio", ratio_json(r.ratio, c.targets)},
          {"data_inconsistencies", inconsistencies_json(r.inconsistencies, c.targets)},
          {"screen", screen_json(r.screen, c)},
          {"next_test",
           next_test_json(r.next_test, c,
                          r.candidates.empty() ? std::vector<std::string>()
                                               : on_bounds(r.candidates.front().calibration.z))},
          {"candidates", candidates},
          {"grid",
           {{"design", c.grid.design == Design::local ? "local" : "global"},
            {"step", c.grid.design == Design::local ? json(c.grid.step) : json(nullptr)},
            {"fr0", c.grid.fr0},
            {"fs0", c.grid.fs0},
            {"s", c.grid.s},
            {"bounds", {{"fr0", {c.fr0_n.lo, c.fr0_n.hi}}, {"fs0", {c.fs0_n.lo, c.fs0_n.hi}}}}}},
          {"runs",
           {{"model_points", r.model_points + r.next_test.model_points},
            // One engine job per distinct test condition of a model point; the next test's
            // points run on the menu's conditions too.
            {"jobs", r.model_points * int(plan_runs(c.targets).runs.size()) +
                         r.next_test.model_points *
                             int(plan_runs(with_menu(c.targets, r.next_test.menu)).runs.size())},
            {"failed_values", r.failed_values},
            {"first_error", r.first_error.empty() ? json(nullptr) : json(r.first_error)}}},
          {"units", "model"}};
}

}  // namespace rockcal::diagnosis
