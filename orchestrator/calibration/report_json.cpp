// to_json of the report. JSON has no NaN: quantities that do not exist are null, never NaN.
#include <cmath>

#include "orchestrator/calibration/bayes/check.hpp"
#include "orchestrator/calibration/bayes/verdict.hpp"
#include "orchestrator/calibration/objective.hpp"
#include "orchestrator/calibration/report.hpp"
#include "orchestrator/calibration/rock_properties.hpp"

namespace rockcal::calibration {
namespace {

using nlohmann::json;

json number_or_null(double x) {
  return std::isfinite(x) ? json(x) : json(nullptr);
}

// One test's result on one specimen: load, strength, target and relative error.
json test_result(double load_n, double target_n, double strength_pa) {
  return {{"peak_load", load_n},
          {"target", target_n},
          {"relative_error", relative_error(load_n, target_n)},
          {"strength", strength_pa}};
}

json loads_json(const PeakLoads& loads, const PeakLoads& targets, const Specimen& specimen) {
  return {{"uct", test_result(loads.uct_n, targets.uct_n, uct_strength_pa(loads.uct_n, specimen))},
          {"btt", test_result(loads.btt_n, targets.btt_n, btt_strength_pa(loads.btt_n, specimen))}};
}

// Each test's realisations and statistics (peak load mean, sd, se, n; failed runs with their
// reason), or null from an evaluator that reports none.
json ensemble_json(const EvaluationRecord& r) {
  if (!r.uct || !r.btt) return nullptr;
  return {{"uct", orch::to_json(*r.uct)}, {"btt", orch::to_json(*r.btt)}};
}

json best_json(const EvaluationRecord& best, const CalibrationCampaign& c) {
  const PeakLoads& targets = c.targets.model_loads_n;
  json j = loads_json(*best.loads, targets, c.model_specimen);
  // The loads are ensemble means: their standard errors and sizes beside them.
  auto spread = [&j](const char* test, const std::optional<orch::Ensemble>& e) {
    j[test]["se"] = e && e->peak_load.se ? json(*e->peak_load.se) : json(nullptr);
    j[test]["n"] = e ? e->peak_load.n : 1;
  };
  spread("uct", best.uct);
  spread("btt", best.btt);
  j["ensemble"] = ensemble_json(best);
  j["fr0"] = best.point.fr0_n;
  j["fs0"] = best.point.fs0_n;
  j["misfit"] = best.misfit;
  j["evaluation"] = best.index;
  j["within_tolerance"] = best.within_tolerance;
  if (c.targets.scaling) {
    const Scaling& s = *c.targets.scaling;
    const BondPoint bonds = bonds_to_lab(best.point, s);
    json lab =
        loads_json(loads_to_lab(*best.loads, s), loads_to_lab(targets, s), c.targets.lab->specimen);
    lab["fr0"] = bonds.fr0_n;
    lab["fs0"] = bonds.fs0_n;
    j["lab"] = lab;
  }
  return j;
}

json mean_se_json(const std::optional<orch::Ensemble>& e, double mean) {
  return {{"mean", mean},
          {"se", e && e->peak_load.se ? json(*e->peak_load.se) : json(nullptr)},
          {"n", e ? e->peak_load.n : 1}};
}

// The consistent set: spans, the points in it, and whether it is one point (with the reason).
json consistent_json(const CalibrationReport& r) {
  const ConsistentSet& set = r.consistent;
  json points = json::array();
  for (const EvaluationRecord& e : set.points) {
    points.push_back({{"fr0", e.point.fr0_n},
                      {"fs0", e.point.fs0_n},
                      {"evaluation", e.index},
                      {"uct", mean_se_json(e.uct, e.loads->uct_n)},
                      {"btt", mean_se_json(e.btt, e.loads->btt_n)}});
  }
  auto range = [&](const Range& x) {
    return set.points.empty() ? json(nullptr) : json{x.lo, x.hi};
  };
  return {{"fr0", range(set.fr0)},
          {"fs0", range(set.fs0)},
          {"ratio", range(set.ratio)},
          {"points", points},
          {"why", set.why},
          {"trace",
           {{"toward_larger_ratio", to_string(r.trace.up)},
            {"toward_smaller_ratio", to_string(r.trace.down)},
            {"evaluations", r.trace.evaluations}}}};
}

json suggestion_json(const std::optional<Suggestion>& s) {
  if (!s) return nullptr;
  json values = json::array();
  for (const ObservableValue& v : s->values) {
    values.push_back({{"fr0", v.point.fr0_n},
                      {"fs0", v.point.fs0_n},
                      {"value", v.value},
                      {"se", v.se ? json(*v.se) : json(nullptr)}});
  }
  json candidates = json::array();
  for (const auto& [name, value] : s->candidates) {
    if (s->expected_shrinkage)
      candidates.push_back({{"observable", name}, {"expected_shrinkage", value}});
    else
      candidates.push_back({{"observable", name}, {"spread", std::expm1(value)}});
  }
  return {{"observable", s->observable},     {"unit", s->unit}, {"values", values},
          {"spread", std::expm1(s->spread)}, {"why", s->why},   {"candidates", candidates}};
}

json targets_json(const CalibrationCampaign& c) {
  const PeakLoads& t = c.targets.model_loads_n;
  json j = {
      {"units", c.targets.lab ? "lab" : "model"},
      {"uct", {{"peak_load", t.uct_n}, {"strength", uct_strength_pa(t.uct_n, c.model_specimen)}}},
      {"btt", {{"peak_load", t.btt_n}, {"strength", btt_strength_pa(t.btt_n, c.model_specimen)}}}};
  if (c.targets.scaling) {
    const Scaling& s = *c.targets.scaling;
    const LabCase& lab = *c.targets.lab;
    const PeakLoads l = loads_to_lab(t, s);
    j["lab"] = {
        {"uct", {{"peak_load", l.uct_n}, {"strength", uct_strength_pa(l.uct_n, lab.specimen)}}},
        {"btt", {{"peak_load", l.btt_n}, {"strength", btt_strength_pa(l.btt_n, lab.specimen)}}}};
    // The lab specimen as the model would have to be to match loads one to one; a model sample of
    // another size matches the mapped loads but not the lab's strengths.
    j["scaling"] = {{"length", s.length},
                    {"force", s.force},
                    {"stress", s.stress},
                    {"time", s.time},
                    {"mass", s.mass},
                    {"velocity", s.velocity},
                    {"kr_lab", s.kr_lab_n_m},
                    {"lab_specimen_in_model_units",
                     {{"diameter", s.length_to_model(lab.specimen.diameter_m)},
                      {"height", s.length_to_model(lab.specimen.height_m)},
                      {"thickness", s.length_to_model(lab.specimen.thickness_m)}}}};
  }
  return j;
}

// How each strength in the report follows from its load: on the model specimen (the engine's own
// definition, the same as its jobs' results) and, with lab targets, on the lab's.
json definitions_json(const CalibrationCampaign& c) {
  json j = {{"model", strength_definitions_json(c.model_specimen)}};
  if (c.targets.lab) j["lab"] = strength_definitions_json(c.targets.lab->specimen);
  return j;
}

json history_json(const std::vector<EvaluationRecord>& history) {
  json rows = json::array();
  double best_so_far = INFINITY;
  for (const EvaluationRecord& r : history) {
    if (r.loads) best_so_far = std::min(best_so_far, r.misfit);
    rows.push_back({{"index", r.index},
                    {"phase", r.phase},
                    {"fr0", r.point.fr0_n},
                    {"fs0", r.point.fs0_n},
                    {"seed", r.sample_seed},
                    {"ok", r.loads.has_value()},
                    {"uct", r.loads ? json(r.loads->uct_n) : json(nullptr)},
                    {"btt", r.loads ? json(r.loads->btt_n) : json(nullptr)},
                    {"misfit", r.misfit},
                    {"best_misfit_so_far", number_or_null(best_so_far)},
                    {"within_tolerance", r.within_tolerance},
                    {"error", r.error},
                    {"ensemble", ensemble_json(r)}});
  }
  return rows;
}

json stats_json(const std::optional<LoadStats>& s) {
  if (!s) return nullptr;
  return {{"mean", s->mean_n},
          {"stddev", s->stddev_n},
          {"cv", s->mean_n > 0 ? s->stddev_n / s->mean_n : 0.0},
          {"runs", s->runs}};
}

json scatter_json(const SeedScatter& s) {
  json runs = json::array();
  for (const ScatterRun& r : s.runs) {
    runs.push_back({{"seed", r.seed},
                    {"uct", r.loads ? json(r.loads->uct_n) : json(nullptr)},
                    {"btt", r.loads ? json(r.loads->btt_n) : json(nullptr)},
                    {"error", r.error}});
  }
  return {{"runs", runs}, {"uct", stats_json(s.uct)}, {"btt", stats_json(s.btt)}};
}

json estimate_json(const ScatterEstimate& e) {
  return {{"cv_uct", e.cv_uct ? json(*e.cv_uct) : json(nullptr)},
          {"cv_btt", e.cv_btt ? json(*e.cv_btt) : json(nullptr)},
          {"runs", e.runs},
          {"needed", e.needed ? json(*e.needed) : json(nullptr)}};
}

json ensemble_json(const EnsembleSize& e, const CalibrationCampaign& c) {
  return {{"chosen", e.automatic ? "auto" : "fixed"},
          {"realisations", e.realisations},
          {"max_realisations", e.automatic ? json(c.max_realisations) : json(nullptr)},
          {"capped", e.capped},
          {"target_relative_se", c.tolerance / 2},
          {"pilot", e.automatic ? estimate_json(e.pilot) : json(nullptr)},
          {"at_best", estimate_json(e.at_best)},
          {"why", e.why}};
}

json check_json(const Homogeneity& h) {
  return {{"measured", h.measured},
          {"base", {{"fr0", h.base.fr0_n}, {"fs0", h.base.fs0_n}}},
          {"scale_factor", h.scale_factor},
          {"exponent_uct", number_or_null(h.exponent_uct)},
          {"exponent_btt", number_or_null(h.exponent_btt)},
          {"holds", h.holds}};
}

json homogeneity_json(const HomogeneityChecks& h) {
  json checks = json::array();
  for (const Homogeneity& c : h.checks) checks.push_back(check_json(c));
  // Nothing measured (the bayes strategy relies on no homogeneity) is no verdict on it: null.
  return {{"holds", h.checks.empty() ? json(nullptr) : json(h.holds())},
          {"degree", h.degree()},
          {"checks", checks}};
}

// While "auto" has not chosen yet there is no size to show; after, the latest evaluation's.
json realisations_so_far(const std::vector<EvaluationRecord>& history,
                         const CalibrationCampaign& c) {
  if (!c.auto_realisations) return c.realisations;
  if (history.empty() || !history.back().uct) return "auto";
  return history.back().uct->realisations.size();
}

// The relative error each load may keep and count as met (bayes/verdict.hpp).
json acceptance_json(const CalibrationCampaign& c) {
  const Acceptance a = acceptance(c);
  return {{"uct", a.uct}, {"btt", a.btt}, {"source", a.widened ? "lab_uncertainty" : "tolerance"}};
}

json predicted_json(const PredictedLoad& l, const CalibrationCampaign& c) {
  json j = {{"target", l.target_n},
            {"mean", l.mean_n},
            {"interval", {l.lo_n, l.hi_n}},
            {"run_interval", {l.run_lo_n, l.run_hi_n}},
            {"relative_error", l.relative_error},
            {"lab_sd", l.lab_sd},
            {"emulator_sd", l.emulator_sd},
            {"run_sd", l.run_sd},
            {"emulator_share", l.emulator_share}};
  if (l.check) {
    const CheckAgreement& a = *l.check;
    j["check"] = {{"runs", a.n},
                  {"mean", a.mean_n},
                  {"predicted", a.predicted_n},
                  {"relative_to_prediction", a.relative_to_prediction},
                  {"relative_error", a.relative_to_target},
                  {"sd", a.sd},
                  {"z", a.z},
                  {"level", kCheckLevel},
                  {"agrees", a.agrees}};
  }
  if (c.targets.scaling) {
    const Scaling& s = *c.targets.scaling;
    j["lab"] = {{"target", s.force_to_lab(l.target_n)},
                {"mean", s.force_to_lab(l.mean_n)},
                {"interval", {s.force_to_lab(l.lo_n), s.force_to_lab(l.hi_n)}}};
  }
  return j;
}

// The further targets' predictions, each with its name and test.
json further_json(const std::vector<PredictedLoad>& loads, const CalibrationCampaign& c) {
  json out = json::array();
  for (std::size_t k = 0; k < loads.size() && k < c.further.size(); ++k) {
    json j = predicted_json(loads[k], c);
    j["name"] = c.further[k].name;
    j["test"] = to_string(c.further[k].test);
    out.push_back(j);
  }
  return out;
}

// The "bayes" strategy's answer: model units, with lab units beside when the targets had them.
json posterior_json(const std::optional<PosteriorSummary>& p, const CalibrationCampaign& c) {
  if (!p) return nullptr;
  json region = json::array();
  for (const RegionSpan& s : p->region) region.push_back({s.j, s.i_lo, s.i_hi});
  json j = {
      {"level", p->level},
      {"estimate", {{"fr0", p->estimate.fr0_n}, {"fs0", p->estimate.fs0_n}}},
      {"fr0", {p->fr0.lo, p->fr0.hi}},
      {"fs0", {p->fs0.lo, p->fs0.hi}},
      {"exact_emulators",
       {{"fr0", {p->fr0_exact.lo, p->fr0_exact.hi}}, {"fs0", {p->fs0_exact.lo, p->fs0_exact.hi}}}},
      {"region",
       {{"fr0_extent", {p->fr0_extent.lo, p->fr0_extent.hi}},
        {"fs0_extent", {p->fs0_extent.lo, p->fs0_extent.hi}},
        {"grid",
         {{"cells", p->grid_cells},
          {"fr0", {p->grid_fr0.lo, p->grid_fr0.hi}},
          {"fs0", {p->grid_fs0.lo, p->grid_fs0.hi}},
          {"scale", "log"}}},
        {"spans", region}}},
      {"bounds_reached", p->bounds_reached},
      {"bounded", p->bounds_reached.empty()},
      {"uct", predicted_json(p->uct, c)},
      {"btt", predicted_json(p->btt, c)},
      {"further", further_json(p->further, c)},
      {"lab_uncertainty",
       {{"uct", p->uct.lab_sd},
        {"btt", p->btt.lab_sd},
        {"source", p->lab_stated ? "request" : "default"}}},
      {"acceptance", acceptance_json(c)},
      {"discrepancy", p->discrepancy},
      {"unique_width", p->unique_width},
      {"unique", p->unique},
      {"why", p->why},
      {"runs", p->runs},
      {"points", p->points},
      {"resolution", p->resolution.empty() ? json(nullptr) : json(p->resolution)},
      {"coarse_runs", p->coarse_runs},
      {"rounds", p->rounds},
      {"checked_at", p->checked_at
                         ? json{{"fr0", p->checked_at->fr0_n}, {"fs0", p->checked_at->fs0_n}}
                         : json(nullptr)},
      {"estimate_moved_after_check", p->estimate_moved()},
      {"check_failed", p->check_failed.empty() ? json(nullptr) : json(p->check_failed)}};
  if (c.targets.scaling) {
    const BondPoint lab = bonds_to_lab(p->estimate, *c.targets.scaling);
    const Scaling& s = *c.targets.scaling;
    j["lab"] = {{"estimate", {{"fr0", lab.fr0_n}, {"fs0", lab.fs0_n}}},
                {"fr0", {s.force_to_lab(p->fr0.lo), s.force_to_lab(p->fr0.hi)}},
                {"fs0", {s.force_to_lab(p->fs0.lo), s.force_to_lab(p->fs0.hi)}}};
  }
  return j;
}

json ratio_json(const std::optional<RatioRange>& ratio) {
  if (!ratio) return nullptr;
  return {
      {"target", ratio->target},
      {"min", ratio->min},
      {"max", ratio->max},
      {"emulated", ratio->emulated ? json{{"min", ratio->emulated_lo}, {"max", ratio->emulated_hi}}
                                   : json(nullptr)},
      {"target_inside", ratio->target_inside()}};
}

// The ranges tried, each with its runs' ratio span; the earlier ranges' runs in full (the last
// range's are the report's history).
json reach_json(const std::optional<ReachResult>& reach) {
  if (!reach) return nullptr;
  json tried = json::array();
  for (std::size_t i = 0; i < reach->tried.size(); ++i) {
    const ReachAttempt& a = reach->tried[i];
    const bool last = i + 1 == reach->tried.size();
    tried.push_back({{"interaction_range", a.interaction_range},
                     {"runs", a.history.size()},
                     {"ratio", ratio_json(a.ratio)},
                     {"history", last ? json(nullptr) : history_json(a.history)}});
  }
  return {{"interaction_range", reach->tried.back().interaction_range},
          {"listed", reach->listed},
          {"tried", tried},
          {"why", reach->why}};
}

// Every run the budget paid for: the earlier ranges' and the report's history.
std::size_t runs_of(const CalibrationReport& r) {
  std::size_t n = r.history.size();
  if (r.reach) {
    for (std::size_t i = 0; i + 1 < r.reach->tried.size(); ++i)
      n += r.reach->tried[i].history.size();
  }
  return n;
}

}  // namespace

json to_json(const CalibrationReport& r, const CalibrationCampaign& c) {
  int failed = 0;
  for (const EvaluationRecord& e : r.history) failed += e.loads ? 0 : 1;
  if (r.reach) {
    for (std::size_t i = 0; i + 1 < r.reach->tried.size(); ++i) {
      for (const EvaluationRecord& e : r.reach->tried[i].history) failed += e.loads ? 0 : 1;
    }
  }
  json j = {{"kind", "calibration"},
            {"name", c.name},
            {"stop_reason", to_string(r.stop_reason)},
            {"verdict", to_string(r.verdict)},
            {"verdict_reason", r.verdict_reason},
            {"strategy",
             {{"requested", to_string(c.strategy)},
              {"used", r.strategy_used},
              {"algorithm", c.strategy == Strategy::bayes ? json(nullptr) : json(c.algorithm)}}},
            {"homogeneity", homogeneity_json(r.homogeneity)},
            {"tolerance", c.tolerance},
            {"realisations", r.ensemble.realisations},
            {"ensemble", ensemble_json(r.ensemble, c)},
            {"evaluations", runs_of(r)},
            {"failed_evaluations", failed},
            {"max_evaluations", c.max_evaluations},
            {"consistency_evaluations", c.consistency_evaluations},
            {"targets", targets_json(c)},
            {"strength_definitions", definitions_json(c)},
            {"best", r.best ? best_json(*r.best, c) : json(nullptr)},
            {"rock_properties", rock_properties_json(r, c)},
            {"stiffness", r.stiffness ? to_json(*r.stiffness, c) : json(nullptr)},
            {"history", history_json(r.history)},
            {"scatter", scatter_json(r.scatter)},
            {"consistent", consistent_json(r)},
            {"unique", r.consistent.unique},
            {"suggestion", suggestion_json(r.suggestion)},
            {"fidelity", r.fidelity ? to_json(*r.fidelity, c) : json(nullptr)},
            {"posterior", posterior_json(r.posterior, c)},
            {"reach", reach_json(r.reach)}};
  // Which specimen each evaluation ran on: the template's, coarse when a fine one follows, fine
  // for the bayes strategy's fine runs.
  for (json& row : j["history"]) {
    const std::string phase = row.value("phase", "");
    row["resolution"] = c.fine_patch.is_null()        ? "template"
                        : phase.rfind("fine", 0) == 0 ? "fine"
                                                      : "coarse";
  }
  j["ratio"] = ratio_json(r.ratio);
  if (r.ratio)
    j["ratio"]["best"] = r.best ? json(r.best->loads->uct_n / r.best->loads->btt_n) : json(nullptr);
  return j;
}

json progress_json(const std::vector<EvaluationRecord>& history, const CalibrationCampaign& c) {
  return {{"kind", "calibration"},
          {"name", c.name},
          {"stop_reason", nullptr},
          {"evaluations", history.size()},
          {"max_evaluations", c.max_evaluations},
          {"consistency_evaluations", c.consistency_evaluations},
          {"realisations", realisations_so_far(history, c)},
          {"targets", targets_json(c)},
          {"history", history_json(history)}};
}

}  // namespace rockcal::calibration
