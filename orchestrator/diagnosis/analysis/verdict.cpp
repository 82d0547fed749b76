#include "orchestrator/diagnosis/analysis/verdict.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "orchestrator/diagnosis/analysis/evidence.hpp"
#include "orchestrator/diagnosis/analysis/fit_spread.hpp"
#include "orchestrator/diagnosis/analysis/gap.hpp"

namespace rockcal::diagnosis {
namespace {

std::string fixed(double x, int digits = 3) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", digits, x);
  return buf;
}

bool eligible(const CandidateResult& c) {
  return c.fitted && c.confirmed && c.identifiability && c.identifiability->identifiable &&
         c.fits_calibration && c.evidence.has_value() && !c.inert_at_fit() && !wider_not_closer(c);
}

// "; <effect> (evidence N nats) is not the explanation: <why>" for each effect in `order` that
// `excluded` leaves out and that has evidence above `above`.
template <class Excluded, class Why>
std::string not_the_explanation(const std::vector<CandidateResult>& candidates,
                                const std::vector<int>& order, double above, Excluded excluded,
                                Why why) {
  std::string out;
  for (int i : order) {
    const CandidateResult& c = candidates[i];
    if (!excluded(c) || !c.evidence || !(*c.evidence > above)) continue;
    out += "; " + c.candidate.effect + " (evidence " + fixed(*c.evidence, 2) +
           " nats) is not the explanation: " + why(c);
  }
  return out;
}

// The confirmed effects left out by wider_not_closer whose evidence would have named them; one
// inert at its fit is inert_note's (one reason an effect, the more basic one).
std::string wider_note(const std::vector<CandidateResult>& candidates,
                       const std::vector<int>& order, double min_evidence) {
  return not_the_explanation(
      candidates, order, min_evidence,
      [](const CandidateResult& c) { return wider_not_closer(c) && !c.inert_at_fit(); },
      [](const CandidateResult& c) {
        return "its runs miss the held-out observations by more than the "
               "base model's (G = " +
               fixed(*c.g_confirmed, 2) +
               "), so what it gained is the width of its prediction, not a "
               "closer one";
      });
}

// The confirmed effects whose evidence came from the strengths' re-fit alone: at their fitted
// value they change no observation beyond its noise against the base model at the same strengths.
std::string inert_note(const std::vector<CandidateResult>& candidates,
                       const std::vector<int>& order) {
  return not_the_explanation(
      candidates, order, -std::numeric_limits<double>::infinity(),
      [](const CandidateResult& c) { return c.inert_at_fit(); },
      [](const CandidateResult& c) {
        return "at its fitted value it changes no observation beyond its noise against the base "
               "model at the same strengths (largest change " +
               fixed(*c.mark_at_fit, 2) +
               " of its noise), so what it gained is the strengths' re-fit, not the effect";
      });
}

// The bounds a fit lies on (on_bounds), as a list in a sentence: "fr0 upper, s upper".
std::string bounds_text(const std::vector<std::string>& on) {
  std::string out;
  for (const std::string& b : on) out += (out.empty() ? "" : ", ") + b;
  return out;
}

// The named effect's fit on the search box: there the fit is the bound's, not an optimum, and with
// its parameter at the end of its range the effect may be stronger than the range reaches (a rate
// twin at twice the candidate's strong value is named at it).
std::string fit_on_box_note(const CandidateResult& c) {
  const std::vector<std::string> on = on_bounds(c.calibration.z);
  if (on.empty()) return "";
  std::string note = "; its fit lies on the search box (" + bounds_text(on) + ")";
  if (std::find(on.begin(), on.end(), "s upper") != on.end() && c.candidate.value_at) {
    note += ": " + c.candidate.param + " " + fixed(c.candidate.value_at(1.0), 3) +
            " is the end of the range tried, and the effect may be stronger than that";
  }
  return note + ", so its figures are the bound's, not an optimum's";
}

// The effects that would need a calibration observation to be judged: they move held-out ones
// only (identifiability.hpp).
std::string unfixed_note(const std::vector<CandidateResult>& candidates,
                         const std::vector<int>& order) {
  std::string names;
  int count = 0;
  for (int i : order) {
    const auto& id = candidates[i].identifiability;
    if (id && !id->identifiable && !id->moved.empty()) {
      names += (names.empty() ? "" : ", ") + candidates[i].candidate.effect;
      ++count;
    }
  }
  if (count == 0) return "";
  return " (" + names +
         (count == 1 ? " moves only held-out observations: a calibration observation that it "
                       "moves would fix its parameter)"
                     : " move only held-out observations: a calibration observation that they "
                       "move would fix their parameters)");
}

int group(const CandidateResult& c) {
  if (!c.fitted) return 4;
  if (!c.identifiability || !c.identifiability->identifiable) return 3;
  if (!c.fits_calibration) return 2;
  return c.confirmed ? 0 : 1;
}

}  // namespace

bool leaves_gap(const DecisionRule& rule, std::optional<double> held_out_budgets) {
  return held_out_budgets && *held_out_budgets > rule.gap_budgets;
}

int choose_effect(const DecisionRule& rule, const std::vector<Contender>& contenders,
                  std::optional<double> held_out_budgets) {
  if (!leaves_gap(rule, held_out_budgets)) return -1;
  const Contender* best = nullptr;
  for (const Contender& c : contenders) {
    if (!best || c.evidence > best->evidence) best = &c;
  }
  return best && best->evidence > rule.min_evidence ? best->index : -1;
}

void mark_calibration_fits(std::vector<CandidateResult>& candidates, double combined_calibration) {
  std::optional<double> best;
  for (const CandidateResult& c : candidates) {
    const auto r = c.fitted ? c.rms().calibration : std::nullopt;
    if (r && (!best || *r < *best)) best = r;
  }
  for (CandidateResult& c : candidates) {
    const auto r = c.fitted ? c.rms().calibration : std::nullopt;
    c.fits_calibration =
        r && best &&
        *r <= std::max(*best + combined_calibration, kCalibrationFitBudgets * combined_calibration);
  }
}

bool wider_not_closer(const CandidateResult& c) {
  return c.confirmed && c.g_confirmed && *c.g_confirmed <= 0.0;
}

std::vector<double> predictive_variance(const CandidateResult& c,
                                        const std::vector<Target>& targets,
                                        const std::vector<double>& budget) {
  std::vector<double> v = fit_spread(c.surfaces, c.calibration.z, targets, budget);
  if (c.confirmed) return v;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto& s = i < c.surfaces.per_target.size() ? c.surfaces.per_target[i] : std::nullopt;
    v[i] += s && !c.calibration.z.empty() ? variance_at(*s, c.calibration.z) : NAN;
  }
  return v;
}

std::vector<double> held_out_fit_variance(const CandidateResult& c,
                                          const std::vector<Target>& targets,
                                          const std::vector<double>& budget) {
  std::vector<double> v = fit_spread(c.surfaces, c.calibration.z, targets, budget);
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (targets[i].role != Role::held_out) v[i] = 0.0;
  }
  return v;
}

void mark_evidence(std::vector<CandidateResult>& candidates, const std::vector<Target>& targets,
                   const std::vector<double>& lab, const std::vector<double>& budget) {
  for (CandidateResult& c : candidates) {
    c.density.reset();
    c.evidence.reset();
    if (!c.fitted) continue;
    HeldOutDensity d = held_out_density(residuals(c.ln_sim(), lab), targets, budget,
                                        predictive_variance(c, targets, budget));
    if (!d.terms.empty()) c.density = std::move(d);  // none: no held-out value, or no surface error
  }
  const CandidateResult& base = candidates[0];
  if (!base.confirmed || !base.density) return;
  for (std::size_t k = 1; k < candidates.size(); ++k) {
    CandidateResult& c = candidates[k];
    if (c.density) c.evidence = evidence_over(*c.density, *base.density);
  }
}

std::vector<int> rank_effects(std::vector<CandidateResult>& candidates) {
  std::vector<int> order;
  for (int i = 1; i < int(candidates.size()); ++i) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const CandidateResult& x = candidates[a];
    const CandidateResult& y = candidates[b];
    if (group(x) != group(y)) return group(x) < group(y);
    if (x.evidence && y.evidence) return *x.evidence > *y.evidence;
    if (x.evidence || y.evidence) return x.evidence.has_value();
    return x.g().value_or(-1e300) > y.g().value_or(-1e300);
  });
  for (std::size_t r = 0; r < order.size(); ++r) candidates[order[r]].rank = int(r) + 1;
  return order;
}

std::string verdict_label(const std::vector<CandidateResult>& candidates, int index) {
  return index < 0 ? "no effect needed" : candidates[index].candidate.effect;
}

Verdict decide(const DecisionRule& rule, const std::vector<CandidateResult>& candidates,
               const std::vector<int>& order, std::optional<double> gap, double combined_held_out) {
  Verdict v;
  std::vector<Contender> contenders;
  for (int i : order) {
    if (eligible(candidates[i])) contenders.push_back({i, *candidates[i].evidence});
  }
  const auto base_rms = candidates[0].confirmed_rms.held_out;
  v.candidate = choose_effect(rule, contenders, gap);
  for (const Contender& c : contenders) {
    if (v.best < 0 || c.evidence > *candidates[v.best].evidence) v.best = c.index;
  }
  for (int i : order) {
    if (i != v.candidate) {
      v.runner_up = i;
      break;
    }
  }
  if (!base_rms || !gap) {
    v.reason = "the base model has no held-out residual (its runs failed): nothing to judge";
    return v;
  }
  const std::string size = "the base model's held-out residuals are " + fixed(*gap, 2) +
                           " budgets (rms of each over its own numerical budget and lab "
                           "uncertainty; held-out rms " +
                           fixed(*base_rms) + ", combined budget " + fixed(combined_held_out) + ")";
  const auto evidence_text = [&](int i) {
    return "evidence " + fixed(*candidates[i].evidence, 2) + " nats over the base (threshold " +
           fixed(rule.min_evidence, 2) + ")";
  };
  const bool no_gap = !leaves_gap(rule, gap);
  const std::string gap_text = no_gap ? ": within the " + fixed(rule.gap_budgets, 2) +
                                            " budgets of the decision rule, no gap to explain; "
                                      : ": a gap, but ";
  if (v.candidate >= 0) {
    const CandidateResult& c = candidates[v.candidate];
    v.reason = c.candidate.effect + ": " + evidence_text(v.candidate);
    if (c.g_confirmed) {
      v.reason += "; it closes G = " + fixed(*c.g_confirmed, 2) +
                  " of the held-out gap (held-out rms " + fixed(*base_rms) + " -> " +
                  fixed(c.confirmed_rms.held_out.value_or(0)) + ")";
    }
    v.reason += fit_on_box_note(c) + "; the base model's held-out residuals are " + fixed(*gap, 2) +
                " budgets (combined budget " + fixed(combined_held_out) + ")";
  } else if (contenders.empty()) {
    const std::string inert = inert_note(candidates, order);
    v.reason = size + gap_text +
               (inert.empty() ? "no candidate effect is both identifiable from these observations "
                                "and able to fit the calibration observations"
                              : "no candidate effect is identifiable from these observations, "
                                "able to fit the calibration observations and active at its "
                                "fitted value") +
               unfixed_note(candidates, order) + inert +
               wider_note(candidates, order, rule.min_evidence);
  } else {
    std::string why_not;
    if (!no_gap) {
      why_not = ": none of the candidates explains the gap";
    } else if (*candidates[v.best].evidence > rule.min_evidence) {
      why_not = ", above the threshold, but without a gap there is nothing for it to explain";
    }
    v.reason = size + gap_text + "the best effect, " + candidates[v.best].candidate.effect +
               ", has " + evidence_text(v.best) + why_not + unfixed_note(candidates, order) +
               inert_note(candidates, order) + wider_note(candidates, order, rule.min_evidence);
  }
  return v;
}

namespace {

// Equal element by element, a missing value (NaN) equal only to another missing one.
bool same_values(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] != b[i] && !(std::isnan(a[i]) && std::isnan(b[i]))) return false;
  }
  return true;
}

}  // namespace

std::vector<SeedCheck> seed_checks(const DecisionRule& rule,
                                   const std::vector<CandidateResult>& candidates,
                                   const std::vector<Target>& targets,
                                   const std::vector<std::uint64_t>& seeds,
                                   const std::vector<double>& budget) {
  std::vector<SeedCheck> out;
  const std::vector<double> lab = ln_lab(targets);
  const std::vector<double> base_spread = held_out_fit_variance(candidates[0], targets, budget);
  for (std::size_t j = 0; j < seeds.size(); ++j) {
    if (candidates[0].seed_ln.size() <= j) break;
    SeedCheck check;
    check.seed = seeds[j];
    check.informative = false;
    for (const CandidateResult& c : candidates) {
      if (c.seed_ln.size() > j && !same_values(c.seed_ln[j], c.confirmed_ln)) {
        check.informative = true;
      }
    }
    const std::vector<double> base_residuals = residuals(candidates[0].seed_ln[j], lab);
    const auto base_rms = rms(base_residuals, targets, Role::held_out);
    const HeldOutDensity base_density = held_out_density(
        base_residuals, targets, budget, predictive_variance(candidates[0], targets, budget));
    std::vector<Contender> contenders;
    for (int i = 1; i < int(candidates.size()); ++i) {
      const CandidateResult& c = candidates[i];
      if (!eligible(c) || c.seed_ln.size() <= j) continue;
      const std::vector<double> r = residuals(c.seed_ln[j], lab);
      if (const auto g = gap_closure(rms(r, targets, Role::held_out), base_rms)) {
        check.gap_closure[c.candidate.effect] = *g;
      }
      const auto e = evidence_over(
          held_out_density(r, targets, budget, predictive_variance(c, targets, budget)),
          base_density);
      if (!e) continue;
      check.evidence[c.candidate.effect] = *e;
      contenders.push_back({i, *e});
    }
    const int chosen =
        choose_effect(rule, contenders,
                      rms_in_budgets(base_residuals, targets, budget, Role::held_out, base_spread));
    check.verdict = chosen < 0 ? "" : candidates[chosen].candidate.effect;
    out.push_back(std::move(check));
  }
  return out;
}

std::string confidence_level(const Confidence& c) {
  const int seeds = c.seeds_informative;
  if (c.agreement >= 0.9 && c.seeds_agreeing == seeds) return "high";
  if (c.agreement >= 0.7 && 2 * c.seeds_agreeing > seeds) return "medium";
  if (c.agreement >= 0.7 && seeds == 0) return "medium";
  return "low";
}

std::string verdict_label(const std::vector<CandidateResult>& candidates, const Verdict& v) {
  if (v.undetermined) return "undetermined";
  // No effect named beside a miss beyond the rule (temper_verdict): "no effect needed" would deny
  // the miss the reason states.
  if (v.candidate < 0 && v.miss) return "unexplained miss";
  return verdict_label(candidates, v.candidate);
}

std::vector<std::string> on_bounds(const std::vector<double>& z) {
  constexpr double kOnBound = 1e-3;  // of the unit cube: 0.3% of F on the default log box
  static const char* const names[] = {"fr0", "fs0", "s"};
  std::vector<std::string> out;
  for (std::size_t d = 0; d < z.size() && d < 3; ++d) {
    if (z[d] <= kOnBound) out.push_back(std::string(names[d]) + " lower");
    if (z[d] >= 1.0 - kOnBound) out.push_back(std::string(names[d]) + " upper");
  }
  return out;
}

void temper_verdict(const DecisionRule& rule, const Evidence& e, Verdict& v, Confidence& conf) {
  std::vector<std::string> causes;
  if (e.held_out_observations == 0) {
    causes.push_back("no held-out observations, so no effect can be judged");
  } else if (!e.base_has_held_out) {
    causes.push_back("the base model has no held-out residual (its runs failed)");
  }
  std::string bound_note;
  if (!e.base_on_bounds.empty()) {
    const std::string where = bounds_text(e.base_on_bounds);
    Verdict::Bound& bound = v.bound.emplace();
    bound.on = e.base_on_bounds;
    bound.calibration = e.base.calibration;
    bound.refitted = e.base_calibration_refitted;
    const bool unfit = bound.refitted && *bound.refitted > kCalibrationFitBudgets;
    const bool indifferent = bound.refitted && bound.calibration &&
                             *bound.calibration - *bound.refitted <= kBoundGainBudgets;
    bound.holds = !unfit && !indifferent;
    const std::string beyond =
        "re-fitted beyond it linearly on its sensitivity there, its calibration miss of " +
        (bound.calibration ? fixed(*bound.calibration, 1) : std::string("?")) +
        " noise budgets would be " + (bound.refitted ? fixed(*bound.refitted, 1) : "?");
    if (bound.holds) {
      causes.push_back("the base model's fit lies on the search box (" + where +
                       "): its strengths are the bounds', not the data's (widen the bounds" +
                       (bound.refitted ? ": " + beyond : std::string()) + ")");
    } else {
      bound_note = "; the base model's fit lies on the search box (" + where +
                   "), but the bound does not hold it: " + beyond +
                   (unfit ? ", beyond what a fitting model may leave, so no strengths explain "
                            "its miss"
                          : " (" + fixed(*bound.calibration - *bound.refitted, 2) +
                                " less, within " + fixed(kBoundGainBudgets, 2) +
                                "): the data barely depend on that strength there, so its value "
                                "is the bound's but the fit is not limited by it");
    }
  }
  if (!causes.empty()) {
    v.undetermined = true;
    v.candidate = -1;
    v.reason = "undetermined: ";
    for (const std::string& c : causes) v.reason += c + "; ";
    v.reason += miss_text(e.base, rule.gap_budgets) + bound_note;
    v.miss = e.base;
    conf.level = "none";
    return;
  }
  v.reason += bound_note;
  if (misses_beyond(e.verdict, rule.gap_budgets)) {
    v.reason += "; not explained: " + miss_text(e.verdict, rule.gap_budgets);
    v.miss = e.verdict;
    // No effect named: the label says the miss is unexplained, confidence low. A named effect
    // explains part of it: not high.
    if (v.candidate < 0) {
      conf.level = "low";
    } else if (conf.level == "high") {
      conf.level = "medium";
    }
  }
}

}  // namespace rockcal::diagnosis
