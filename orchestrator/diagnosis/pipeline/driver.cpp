#include "orchestrator/diagnosis/pipeline/driver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "orchestrator/diagnosis/analysis/bootstrap.hpp"
#include "orchestrator/diagnosis/analysis/consistency.hpp"
#include "orchestrator/diagnosis/analysis/gap.hpp"
#include "orchestrator/diagnosis/analysis/identifiability.hpp"
#include "orchestrator/diagnosis/analysis/ratio.hpp"
#include "orchestrator/diagnosis/analysis/screen.hpp"
#include "orchestrator/diagnosis/analysis/trust_region.hpp"
#include "orchestrator/diagnosis/analysis/verdict.hpp"
#include "orchestrator/diagnosis/pipeline/grid.hpp"
#include "orchestrator/diagnosis/pipeline/local_design.hpp"
#include "orchestrator/diagnosis/pipeline/next_test_runs.hpp"

namespace rockcal::diagnosis {
namespace {

using nlohmann::json;

// Five phases, and the next test's sixth when the campaign asks for it.
void phase(const DiagnosisOptions& o, const DiagnosisCampaign& c, const std::string& name, int step,
           int runs) {
  if (o.stop.stop_requested()) throw DiagnosisCancelled();
  if (o.on_progress) {
    o.on_progress(
        {{"phase", name}, {"step", step}, {"steps", c.next_test ? 6 : 5}, {"runs", runs}});
  }
}

bool has_weight(const Objective& o) {
  return std::any_of(o.weight.begin(), o.weight.end(), [](double w) { return w > 0; });
}

std::string first_error(const Samples& s) {
  for (const RunOutcome& o : s.outcomes) {
    if (!o.error.empty()) return o.error;
  }
  return "";
}

// The calibration of one candidate on its surfaces, and what it predicts.
void fit_candidate(CandidateResult& r, const DiagnosisCampaign& c, const std::vector<double>& lab,
                   const std::vector<double>& budget, const CandidateResult& base) {
  const Objective objective = calibration_objective(c.targets, budget, r.surfaces, lab);
  if (!has_weight(objective)) {
    r.error = "no calibration observation has a response surface (too many failed runs)";
    return;
  }
  r.calibration = calibrate_on_surfaces(r.surfaces, objective, lattice_starts(r.surfaces.dims, 3));
  r.point = model_point(c, r.candidate, r.calibration.z);
  if (!r.candidate.is_base()) {
    r.value = r.candidate.value_at ? r.candidate.value_at(r.point.s) : r.point.s;
  }
  r.predicted = predict(r.surfaces, r.calibration.z);
  const std::vector<double> res = residuals(r.predicted, lab);
  r.surface_rms = {rms(res, c.targets, Role::calibration), rms(res, c.targets, Role::held_out)};
  r.fitted = true;
  if (!r.candidate.is_base()) {
    r.identifiability = identifiability(r.surfaces, objective, c.targets, budget, 11,
                                        r.candidate.shares_base_grid() ? nullptr : &base.predicted);
  }
}

// Base first, then up to `confirm` identifiable effects that fit the calibration observations, by
// surface G.
std::vector<int> to_confirm(const std::vector<CandidateResult>& candidates, int confirm) {
  std::vector<int> effects;
  for (int i = 1; i < int(candidates.size()); ++i) {
    const CandidateResult& r = candidates[i];
    if (r.fitted && r.identifiability->identifiable && r.fits_calibration && r.g_surface) {
      effects.push_back(i);
    }
  }
  std::stable_sort(effects.begin(), effects.end(), [&](int a, int b) {
    return *candidates[a].g_surface > *candidates[b].g_surface;
  });
  if (int(effects.size()) > confirm) effects.resize(confirm);
  effects.insert(effects.begin(), 0);
  return effects;
}

// The real calibration misfit of a run; infinite when a calibration observation has no value (a
// failed run must not look like a good fit).
double real_misfit(const Objective& objective, const std::vector<double>& ln_sim) {
  for (std::size_t i = 0; i < ln_sim.size(); ++i) {
    if (objective.weight[i] > 0 && !std::isfinite(ln_sim[i])) {
      return std::numeric_limits<double>::infinity();
    }
  }
  return misfit(objective, ln_sim);
}

std::vector<double> offset_of(const std::vector<double>& real, const std::vector<double>& surface) {
  std::vector<double> out(real.size(), 0.0);
  for (std::size_t i = 0; i < real.size(); ++i) {
    if (std::isfinite(real[i]) && std::isfinite(surface[i])) out[i] = real[i] - surface[i];
  }
  return out;
}

// A surface misses a run by its interpolation error (the leave-one-out rms: 0.1-0.3 in ln on a
// coarse grid), far more than lab noise, so a fit on the surfaces alone lands off the real optimum
// and the real residuals there mix fit error into the gap. Each chosen candidate is therefore run
// at its surface fit, its surfaces are shifted to pass through that run, re-fitted, and run again
// (`refine` times, or until the fit stops moving); the run with the smallest real calibration
// misfit is the candidate's confirmed point. The design's own runs of the candidate count as runs
// made: a surface fit far from them (a wide box, a coarse grid) that the real run refutes is then
// left for the best of them, not kept because it was the only trial. Then the replicate seeds run
// there.
void confirm_candidates(std::vector<CandidateResult>& candidates, const DiagnosisCampaign& c,
                        const std::vector<int>& chosen, const std::vector<Samples>& samples,
                        Evaluator& evaluator, const std::vector<double>& lab,
                        const std::vector<double>& budget) {
  const Numerics nominal{c.sample_seed, 1.0, 1.0};
  constexpr double kSettled = 0.01;  // unit-cube step below which a re-fit counts as settled
  constexpr double kMaxStep = 0.25;  // first trust radius: the longest unit-cube step of a re-fit
  struct State {
    std::vector<double> z;  // the next trial
    bool active = true;
    TrustRegion trust{kMaxStep};
  };
  std::vector<State> state(chosen.size());
  for (std::size_t j = 0; j < chosen.size(); ++j) {
    const CandidateResult& r = candidates[chosen[j]];
    state[j].z = r.calibration.z;
    const Objective objective = calibration_objective(c.targets, budget, r.surfaces, lab);
    const Samples& made = samples[std::size_t(chosen[j])];
    for (std::size_t t = 0; t < made.z.size(); ++t) {
      const std::vector<double> ln = ln_values(made.outcomes[t]);
      state[j].trust.start_from(made.z[t], real_misfit(objective, ln), ln);
    }
  }
  for (int step = 0; step <= c.refine; ++step) {
    std::vector<RunRequest> requests;
    std::vector<std::size_t> who;
    for (std::size_t j = 0; j < chosen.size(); ++j) {
      if (!state[j].active) continue;
      requests.push_back({model_point(c, candidates[chosen[j]].candidate, state[j].z), nominal});
      who.push_back(j);
    }
    if (requests.empty()) break;
    const std::vector<RunOutcome> outcomes = evaluator.run_batch(requests);
    for (std::size_t k = 0; k < who.size(); ++k) {
      State& st = state[who[k]];
      CandidateResult& r = candidates[chosen[who[k]]];
      const Objective objective = calibration_objective(c.targets, budget, r.surfaces, lab);
      const std::vector<double> ln = ln_values(outcomes[k]);
      const double m = real_misfit(objective, ln);
      r.refinement.push_back({requests[k].point, m});
      // A worse run shortens the next step (without it the D = 8 null twins' base fits bounced
      // between two points a step apart, F_r0 32 and 64, never nearing the truth between them).
      st.trust.record(st.z, m, ln);
      if (step == c.refine) {
        st.active = false;
        continue;
      }
      // The next step starts from the best run, on the surfaces shifted through it (after a worse
      // run: the same direction, half as far). The shift is exact only at the run, so a long step
      // trusts the surface's shape far away, which on a coarse grid is what failed first.
      const TrustRegion& t = st.trust;
      const SurfaceCalibration fit = refit_near(
          r.surfaces, objective, t.best_z, offset_of(t.best_ln, predict(r.surfaces, t.best_z)));
      const auto z = st.trust.next(fit.z, kSettled);
      if (z) {
        st.z = *z;
      } else {
        st.active = false;
      }
    }
  }

  std::vector<RunRequest> seed_requests;
  for (std::size_t j = 0; j < chosen.size(); ++j) {
    CandidateResult& r = candidates[chosen[j]];
    const TrustRegion& st = state[j].trust;
    r.calibration.z = st.best_z;
    r.point = model_point(c, r.candidate, st.best_z);
    if (!r.candidate.is_base()) {
      r.value = r.candidate.value_at ? r.candidate.value_at(r.point.s) : r.point.s;
    }
    r.predicted = predict(r.surfaces, st.best_z);
    const std::vector<double> predicted_res = residuals(r.predicted, lab);
    r.surface_rms = {rms(predicted_res, c.targets, Role::calibration),
                     rms(predicted_res, c.targets, Role::held_out)};
    r.surface_offset = offset_of(st.best_ln, r.predicted);
    r.confirmed = true;
    r.confirmed_ln = st.best_ln;
    const std::vector<double> res = residuals(r.confirmed_ln, lab);
    r.confirmed_rms = {rms(res, c.targets, Role::calibration), rms(res, c.targets, Role::held_out)};
    for (std::uint64_t seed : c.budget.seeds) seed_requests.push_back({r.point, {seed, 1.0, 1.0}});
    // The effect's own mark at its fitted value: the base model at the same strengths.
    if (!r.candidate.is_base()) {
      const std::vector<double> strengths(st.best_z.begin(), st.best_z.begin() + 2);
      seed_requests.push_back({model_point(c, candidates[0].candidate, strengths), nominal});
    }
  }
  const std::vector<RunOutcome> outcomes = evaluator.run_batch(seed_requests);
  std::size_t k = 0;
  for (int i : chosen) {
    CandidateResult& r = candidates[i];
    for (std::size_t s = 0; s < c.budget.seeds.size(); ++s)
      r.seed_ln.push_back(ln_values(outcomes[k++]));
    if (r.candidate.is_base()) continue;
    const std::vector<double> base_ln = ln_values(outcomes[k++]);
    for (std::size_t t = 0; t < c.targets.size(); ++t) {
      if (!std::isfinite(base_ln[t]) || !std::isfinite(r.confirmed_ln[t])) continue;
      const double m = std::abs(r.confirmed_ln[t] - base_ln[t]) / (budget[t] + c.targets[t].sigma);
      r.mark_at_fit = std::max(r.mark_at_fit.value_or(0.0), m);
    }
  }
  for (int i : chosen) {
    candidates[i].g_confirmed =
        gap_closure(candidates[i].confirmed_rms.held_out, candidates[0].confirmed_rms.held_out);
  }
  candidates[0].g_confirmed.reset();
}

// Every variant at the base fit and its neighbours (budget_points), one batch; `extra` runs go in
// the same batch, and `extra_outcomes` gets the nominal run at z, then theirs.
Budget measure_budget(const DiagnosisCampaign& c, const CandidateResult& base,
                      const std::vector<double>& z, Evaluator& evaluator,
                      const std::vector<RunRequest>& extra = {},
                      std::vector<RunOutcome>* extra_outcomes = nullptr) {
  std::vector<BudgetVariant> variants = budget_variants(c.budget, c.sample_seed, c.dataset.origin);
  const std::vector<std::vector<double>> points = budget_points(z, c.budget.points);
  std::vector<RunRequest> requests;
  for (const std::vector<double>& at : points) {
    const ModelPoint point = model_point(c, base.candidate, at);
    requests.push_back({point, {c.sample_seed, 1.0, 1.0}});
    for (const BudgetVariant& v : variants) requests.push_back({point, v.numerics});
  }
  const std::size_t budget_runs = requests.size();
  requests.insert(requests.end(), extra.begin(), extra.end());
  std::vector<RunOutcome> outcomes = evaluator.run_batch(requests);
  if (extra_outcomes) {
    extra_outcomes->assign(outcomes.begin() + budget_runs, outcomes.end());
    extra_outcomes->insert(extra_outcomes->begin(), outcomes.front());
  }
  outcomes.resize(budget_runs);
  const std::size_t per_point = 1 + variants.size();
  std::vector<RunOutcome> references;
  std::vector<std::vector<RunOutcome>> changed;
  for (std::size_t k = 0; k < outcomes.size(); k += per_point) {
    references.push_back(outcomes[k]);
    changed.emplace_back(outcomes.begin() + k + 1, outcomes.begin() + k + per_point);
  }
  const StrengthResponse response = strength_response(base.surfaces, c.targets, points);
  return numerical_budget(std::move(variants), references, changed, &response);
}

// The screen's second point, the balanced one: equal strengths F_r0 = F_s0 at the base fit's
// geometric mean, each within its bounds, on the study's lattice; none when that lies within 1.5
// grid steps of z on both axes. The base fit's ratio F_s0 / F_r0 sets which bond failure rules the
// peaks, and an effect that acts through one of them is invisible where the other rules; a hidden
// effect can put the base fit in the wrong regime (the compression-coupling twin at D/R 20: base
// fit (256, 27.9) N, the truth's (68.4, 87.5) N, the coupling, which weighs a bond's compression by
// 1 / F_r0, without a mark at the first), so the screen also looks where neither rules alone.
std::optional<std::vector<double>> balanced_point(const DiagnosisCampaign& c,
                                                  const std::vector<double>& z) {
  const ModelPoint at = model_point(c, Candidate{}, z);
  const double mean = 0.5 * (std::log(at.fr0_n) + std::log(at.fs0_n));
  auto unit = [&](const calibration::Range& r) {
    return std::clamp((mean - std::log(r.lo)) / (std::log(r.hi) - std::log(r.lo)), 0.0, 1.0);
  };
  const std::vector<double> b = study_point(c, {unit(c.fr0_n), unit(c.fs0_n)});
  const double near = 1.5 * c.grid.step;
  if (std::abs(b[0] - z[0]) < near && std::abs(b[1] - z[1]) < near) return std::nullopt;
  return b;
}

// The steps of an effect's own sensitivity at a screen point: the local design's arms (so an
// effect designed where it was screened re-uses these runs), inward at the box's upper face.
std::array<double, 2> screen_steps(const DiagnosisCampaign& c, const std::vector<double>& z) {
  std::array<double, 2> step{};
  for (std::size_t d = 0; d < 2; ++d)
    step[d] = z[d] + c.grid.step <= 1.0 ? c.grid.step : -c.grid.step;
  return step;
}

// Each effect's runs at s = 1 at a screen point z (kScreenRunsPerEffect: at z and a step along
// each strength).
void add_screen_runs(const DiagnosisCampaign& c, const std::vector<double>& z,
                     std::vector<RunRequest>& requests) {
  const Numerics nominal{c.sample_seed, 1.0, 1.0};
  const std::array<double, 2> step = screen_steps(c, z);
  for (const Candidate& k : c.candidates) {
    for (const std::vector<double>& at :
         {std::vector<double>{z[0], z[1], 1.0}, std::vector<double>{z[0] + step[0], z[1], 1.0},
          std::vector<double>{z[0], z[1] + step[1], 1.0}})
      requests.push_back({model_point(c, k, at), nominal});
  }
}

// Every effect judged at screen point z from its runs there (`runs`, add_screen_runs' order) and
// the base model's nominal run at z; fit_shift from z.
std::vector<ScreenedEffect> screen_at(const DiagnosisCampaign& c, const CandidateResult& base,
                                      const std::vector<double>& z, const RunOutcome& base_run,
                                      const RunOutcome* runs, const std::vector<double>& budget) {
  const StrengthResponse response = strength_response(base.surfaces, c.targets, {z});
  const std::array<double, 2> step = screen_steps(c, z);
  std::vector<ScreenedEffect> out;
  for (std::size_t k = 0; k < c.candidates.size(); ++k) {
    const RunOutcome* own = runs + kScreenRunsPerEffect * k;
    out.push_back(screen_effect(c.candidates[k].effect, base_run, own[0], response.jacobian[0],
                                response.weight, c.targets, budget));
    out.back().fit_shift = fit_shift(
        own[0], c.targets, secant_jacobian(own[0], {own[1], own[2]}, step), response.weight);
  }
  return out;
}

// The budget at the base model's first fit z, and in the same batch every effect at s = 1 there
// (screen.hpp) when the campaign screens: judged against that budget, compared with the base's
// nominal run at z (the budget's first reference); and at the balanced point (balanced_point), an
// effect with no mark at z kept when it shows one there, its design centred on its fit from there.
Budget budget_and_screen(const DiagnosisCampaign& c, const CandidateResult& base,
                         const std::vector<double>& z, Evaluator& evaluator, ScreenResult& screen) {
  screen.enabled = c.screen && !c.candidates.empty();
  if (!screen.enabled) return measure_budget(c, base, z, evaluator);
  screen.point = model_point(c, base.candidate, z);
  screen.z = z;
  const auto balanced = balanced_point(c, z);
  std::vector<RunRequest> requests;
  add_screen_runs(c, z, requests);
  if (balanced) {
    screen.balanced_z = *balanced;
    screen.balanced_point = model_point(c, base.candidate, *balanced);
    requests.push_back({screen.balanced_point, {c.sample_seed, 1.0, 1.0}});
    add_screen_runs(c, *balanced, requests);
  }
  std::vector<RunOutcome> outcomes;
  Budget budget = measure_budget(c, base, z, evaluator, requests, &outcomes);
  screen.effects = screen_at(c, base, z, outcomes[0], &outcomes[1], budget.per_target);
  screen.model_points = kScreenRunsPerEffect * int(c.candidates.size());
  if (balanced) {
    const std::size_t at = 1 + kScreenRunsPerEffect * c.candidates.size();
    const std::vector<ScreenedEffect> there =
        screen_at(c, base, *balanced, outcomes[at], &outcomes[at + 1], budget.per_target);
    screen.model_points += 1 + kScreenRunsPerEffect * int(c.candidates.size());
    for (std::size_t k = 0; k < there.size(); ++k) {
      ScreenedEffect& e = screen.effects[k];
      if (e.visible || !there[k].visible) continue;
      e = there[k];
      e.at_balanced = true;
      // Its fit from the balanced point, as a shift from the base fit's.
      for (std::size_t d = 0; d < 2; ++d) e.fit_shift[d] += (*balanced)[d] - z[d];
    }
  }
  for (std::size_t k = 0; k < c.candidates.size(); ++k) {
    if (!screen.effects[k].visible && judges_effects(c)) {
      screen.skipped_model_points += effect_grid_points(c, c.candidates[k]);
    }
  }
  return budget;
}

// The campaign with only the effects it designs: those the screen kept, none when nothing is held
// out (no evidence could judge them; the next test names what would). `shifts` gets the kept
// effects' fit_shift (empty when not screened).
DiagnosisCampaign kept_effects(const DiagnosisCampaign& c, const ScreenResult& screen,
                               std::vector<std::array<double, 2>>& shifts) {
  DiagnosisCampaign kept = c;
  shifts.clear();
  if (!screen.enabled && judges_effects(c)) return kept;
  kept.candidates.clear();
  if (!judges_effects(c)) return kept;
  for (std::size_t k = 0; k < c.candidates.size(); ++k) {
    if (!screen.effects[k].visible) continue;
    kept.candidates.push_back(c.candidates[k]);
    shifts.push_back(screen.effects[k].fit_shift);
  }
  return kept;
}

// The base model's calibration rms in noise budgets with its strengths re-fitted freely (beyond
// the box), linearly on its surfaces' sensitivity at its fit, weighted as the miss is judged.
std::optional<double> calibration_refitted(const std::vector<Target>& targets,
                                           const CandidateResult& base,
                                           const std::vector<double>& lab,
                                           const std::vector<double>& budget) {
  const StrengthResponse response = strength_response(base.surfaces, targets, {base.calibration.z});
  std::vector<double> weight(targets.size(), 0.0);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const double scale = noise_scale(targets[i], budget[i]);
    if (targets[i].role == Role::calibration) weight[i] = 1.0 / (scale * scale);
  }
  const std::vector<double> left =
      change_after_refit(residuals(base.confirmed_ln, lab), response.jacobian[0], weight);
  return rms_in_budgets(left, targets, budget, Role::calibration);
}

// How many of samples[k]'s runs are candidate k's own: those of an effect that shares the base
// grid end with the base's, counted once, as the base's.
std::size_t own_runs(const std::vector<Samples>& samples, const DiagnosisCampaign& c,
                     std::size_t k) {
  const bool shared = k > 0 && c.candidates[k - 1].shares_base_grid();
  return samples[k].outcomes.size() - (shared ? samples[0].outcomes.size() : 0);
}

// Values the grids left missing, and the first reason. The samples of every effect that shares the
// base grid end with it: those are counted once.
void count_failures(DiagnosisResult& report, const DiagnosisCampaign& c,
                    const std::vector<Samples>& samples) {
  report.base_grid_failures.assign(
      samples[0].outcomes.empty() ? 0 : samples[0].outcomes[0].values.size(), 0);
  for (const RunOutcome& o : samples[0].outcomes) {
    for (std::size_t i = 0; i < o.values.size(); ++i) report.base_grid_failures[i] += !o.values[i];
  }
  for (std::size_t k = 0; k < samples.size(); ++k) {
    for (std::size_t r = 0; r < own_runs(samples, c, k); ++r) {
      const RunOutcome& o = samples[k].outcomes[r];
      report.failed_values += int(std::count(o.values.begin(), o.values.end(), std::nullopt));
      if (report.first_error.empty()) report.first_error = o.error;
    }
  }
}

}  // namespace

DiagnosisResult run_diagnosis(const DiagnosisCampaign& campaign, Evaluator& evaluator,
                              const DiagnosisOptions& options) {
  const std::size_t n = campaign.targets.size();
  const std::vector<double> lab = ln_lab(campaign.targets);
  DiagnosisResult report;

  // 1. The base model's response-surface runs: its grid (and, local design, a star at its fit).
  const bool local = campaign.grid.design == Design::local;
  phase(options, campaign, "grid", 1, base_grid_points(campaign));
  std::vector<Samples> samples{local ? run_local_base(campaign, evaluator)
                                     : run_base_grid(campaign, evaluator)};
  report.candidates.resize(1);
  report.candidates[0].surfaces = fit_surfaces(samples[0], 2, n);
  report.model_points = int(samples[0].z.size());

  // 2. The budget, at the base model's fit with lab uncertainties alone (the budget is not known
  // yet); later fits weight each residual by lab uncertainty and budget together. The screen's
  // runs go in its batch.
  const std::optional<SurfaceCalibration> fitted_first =
      fit_on_lab(campaign, report.candidates[0].surfaces);
  if (!fitted_first) {
    throw std::runtime_error(
        "the base model has no response surface for any calibration "
        "observation: its grid runs failed (" +
        first_error(samples[0]) + ")");
  }
  const SurfaceCalibration& base_first = *fitted_first;
  // The local design measures the budget on its lattice, so that datasets on one template share
  // these runs too (study_point).
  const std::vector<double> first_budget_z = study_point(campaign, base_first.z);
  report.weight_budget_point =
      model_point(campaign, report.candidates[0].candidate, first_budget_z);
  const int runs_per_point = int(budget_runs_per_point(campaign.budget, campaign.dataset.origin));
  phase(options, campaign, "budget", 2,
        int(budget_offsets(campaign.budget.points).size()) * runs_per_point +
            screen_model_points(campaign));
  report.weight_budget =
      budget_and_screen(campaign, report.candidates[0], first_budget_z, evaluator, report.screen);
  report.model_points += report.weight_budget.points * runs_per_point + report.screen.model_points;
  const std::vector<double>& budget = report.weight_budget.per_target;

  // 3. The surfaces' runs of every effect the screen kept; from here on the campaign is theirs.
  std::vector<std::array<double, 2>> fit_shifts;
  const DiagnosisCampaign c = kept_effects(campaign, report.screen, fit_shifts);
  phase(options, campaign, "surfaces", 3, grid_points(c) - base_grid_points(c));
  if (local) {
    run_local_effects(c, evaluator, samples, fit_shifts);
  } else {
    run_effect_grids(c, evaluator, samples);
  }
  report.candidates.resize(1 + c.candidates.size());
  for (std::size_t k = 1; k < report.candidates.size(); ++k) {
    CandidateResult& r = report.candidates[k];
    r.candidate = c.candidates[k - 1];
    r.surfaces = fit_surfaces(samples[k], r.candidate.dims(), n);
  }
  for (std::size_t k = 1; k < samples.size(); ++k)
    report.model_points += int(own_runs(samples, c, k));
  report.combined_calibration = combined_budget(c.targets, budget, Role::calibration);

  // 3. Every candidate calibrated on its surfaces; held-out predicted; identifiability.
  for (CandidateResult& r : report.candidates)
    fit_candidate(r, c, lab, budget, report.candidates[0]);
  if (!report.candidates[0].fitted) throw std::runtime_error(report.candidates[0].error);
  for (std::size_t k = 1; k < report.candidates.size(); ++k) {
    CandidateResult& r = report.candidates[k];
    if (r.fitted) {
      r.g_surface = gap_closure(r.surface_rms.held_out, report.candidates[0].surface_rms.held_out);
    }
  }

  // 4. The base and the best candidates by real runs, with the replicate seeds.
  mark_calibration_fits(report.candidates, report.combined_calibration);
  const std::vector<int> chosen = to_confirm(report.candidates, c.confirm);
  phase(options, campaign, "confirm", 4,
        int(chosen.size() * (1 + c.refine + c.budget.seeds.size()) + chosen.size() - 1) +
            int(budget_offsets(c.budget.points).size()) * runs_per_point);
  confirm_candidates(report.candidates, c, chosen, samples, evaluator, lab, budget);
  for (int i : chosen) {
    const CandidateResult& r = report.candidates[i];
    // The effects' base run at their strengths (mark_at_fit) is a model point too.
    report.model_points +=
        int(r.refinement.size() + c.budget.seeds.size()) + !r.candidate.is_base();
  }
  // The budget of the model the residuals come from: re-measured at the confirmed base fit unless
  // that kept the first fit's points (on the demo twins the fit moved up to x7 along F_r0).
  const std::vector<double> base_z = study_point(c, report.candidates[0].calibration.z);
  report.budget = report.weight_budget;
  report.budget_point = report.weight_budget_point;
  if (budget_points(base_z, c.budget.points) != budget_points(first_budget_z, c.budget.points)) {
    report.budget = measure_budget(c, report.candidates[0], base_z, evaluator);
    report.budget_point = model_point(c, report.candidates[0].candidate, base_z);
    report.model_points += report.budget.points * runs_per_point;
  }
  const std::vector<double>& judged = report.budget.per_target;
  report.combined_calibration = combined_budget(c.targets, judged, Role::calibration);
  report.combined_held_out = combined_budget(c.targets, judged, Role::held_out);

  // 5. Evidence, ranking, verdict, confidence.
  phase(options, campaign, "analysis", 5, 0);
  mark_calibration_fits(report.candidates, report.combined_calibration);
  mark_evidence(report.candidates, c.targets, lab, judged);
  const std::vector<int> order = rank_effects(report.candidates);
  // The gap counts the spread the calibration leaves in each held-out prediction, so a held-out
  // observation the calibration leaves loose is no gap by that looseness alone.
  const std::vector<double> base_spread =
      held_out_fit_variance(report.candidates[0], c.targets, judged);
  report.held_out_budgets = rms_in_budgets(residuals(report.candidates[0].confirmed_ln, lab),
                                           c.targets, judged, Role::held_out, base_spread);
  report.verdict = decide(c.decision, report.candidates, order, report.held_out_budgets,
                          report.combined_held_out);
  Confidence& conf = report.confidence;
  conf.seeds = seed_checks(c.decision, report.candidates, c.targets, c.budget.seeds, judged);
  const std::string verdict = report.verdict.candidate < 0
                                  ? ""
                                  : report.candidates[report.verdict.candidate].candidate.effect;
  for (const SeedCheck& s : conf.seeds) {
    conf.seeds_informative += s.informative;
    conf.seeds_agreeing += s.informative && s.verdict == verdict;
  }
  const BootstrapResult boot = bootstrap_verdicts(c.decision, report.candidates, c.targets, budget,
                                                  judged, c.bootstrap, c.random_seed);
  conf.replicates = boot.replicates;
  conf.winners = boot.winners;
  if (boot.replicates > 0) {
    const auto it = boot.winners.find(verdict);
    conf.agreement = it == boot.winners.end() ? 0.0 : double(it->second) / boot.replicates;
  } else {
    conf.agreement = 1.0;
  }
  conf.level = confidence_level(conf);
  report.ratio = ratio_range(c.targets, samples[0].outcomes);
  count_failures(report, c, samples);
  const int chosen_effect = report.verdict.candidate;
  Evidence evidence;
  evidence.held_out_observations = int(count_role(c.targets, Role::held_out));
  evidence.base_has_held_out = report.candidates[0].confirmed_rms.held_out.has_value();
  evidence.base_on_bounds = on_bounds(report.candidates[0].calibration.z);
  if (!evidence.base_on_bounds.empty()) {
    evidence.base_calibration_refitted =
        calibration_refitted(c.targets, report.candidates[0], lab, judged);
  }
  evidence.base =
      model_miss("the base model", c.targets, residuals(report.candidates[0].confirmed_ln, lab),
                 judged, base_spread, c.decision.gap_budgets);
  evidence.verdict =
      chosen_effect < 0
          ? evidence.base
          : model_miss("the model with " + report.candidates[chosen_effect].candidate.effect,
                       c.targets, residuals(report.candidates[chosen_effect].confirmed_ln, lab),
                       judged,
                       held_out_fit_variance(report.candidates[chosen_effect], c.targets, judged),
                       c.decision.gap_budgets);
  temper_verdict(c.decision, evidence, report.verdict, conf);
  if (report.verdict.candidate >= 0)
    report.gap_closure_beyond_noise =
        gap_closure_beyond_noise(evidence.verdict.held_out, evidence.base.held_out);
  // Without held-out residuals there is nothing to judge; say what stopped the runs.
  if (evidence.held_out_observations > 0 && !evidence.base_has_held_out &&
      !report.first_error.empty()) {
    report.verdict.reason += " (first failure: " + report.first_error + ")";
  }
  // A gap left unexplained (not undetermined: then the data judged nothing) may lie with an effect
  // these tests cannot see: say which were dropped.
  const std::string invisible = screened_out_text(report.screen.effects, c.targets);
  if (chosen_effect < 0 && !report.verdict.undetermined && !invisible.empty() &&
      leaves_gap(c.decision, report.held_out_budgets)) {
    report.verdict.reason += "; " + invisible;
  }
  report.inconsistencies = find_inconsistencies(c.targets);
  if (!report.inconsistencies.empty()) {
    report.verdict.reason += "; the data disagree with themselves: " +
                             inconsistency_text(report.inconsistencies, c.targets) +
                             ": no model meets both, so only a residual beyond the span of their "
                             "values is charged to the model";
  }

  // 6. The next test: the lab test that would best tell the leading hypotheses apart, and the one
  // that would make each effect the calibration cannot identify visible.
  if (campaign.next_test) {
    phase(options, campaign, "next_test", 6, next_test_model_points(campaign));
    report.next_test = run_next_test(campaign, report, evaluator);
  }
  return report;
}

}  // namespace rockcal::diagnosis
