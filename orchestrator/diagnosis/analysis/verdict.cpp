#include "orchestrator/diagnosis/analysis/verdict.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

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
         c.fits_calibration && c.g_confirmed.has_value();
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

int choose_effect(const DecisionRule& rule, std::optional<double> base_held_out_budgets,
                  const std::vector<Contender>& contenders) {
  if (!base_held_out_budgets || !(*base_held_out_budgets > rule.gap_budgets)) return -1;
  const Contender* best = nullptr;
  for (const Contender& c : contenders) {
    if (!best || c.g > best->g) best = &c;
  }
  return best && best->g >= rule.min_gap_closure ? best->index : -1;
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

std::vector<int> rank_effects(std::vector<CandidateResult>& candidates) {
  std::vector<int> order;
  for (int i = 1; i < int(candidates.size()); ++i) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const CandidateResult& x = candidates[a];
    const CandidateResult& y = candidates[b];
    if (group(x) != group(y)) return group(x) < group(y);
    const double gx = x.g().value_or(-1e300), gy = y.g().value_or(-1e300);
    return gx > gy;
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
    if (eligible(candidates[i])) contenders.push_back({i, *candidates[i].g_confirmed});
  }
  const auto base_rms = candidates[0].confirmed_rms.held_out;
  v.candidate = choose_effect(rule, gap, contenders);
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
  if (!(*gap > rule.gap_budgets)) {
    v.reason = size + ": within the " + fixed(rule.gap_budgets, 2) +
               " budgets of the decision rule, no gap to explain";
  } else if (v.candidate >= 0) {
    const CandidateResult& c = candidates[v.candidate];
    v.reason = c.candidate.effect + " closes G = " + fixed(*c.g_confirmed, 2) +
               " of the held-out gap (held-out rms " + fixed(*base_rms) + " -> " +
               fixed(c.confirmed_rms.held_out.value_or(0)) + "); the base model's held-out " +
               "residuals are " + fixed(*gap, 2) + " budgets (combined budget " +
               fixed(combined_held_out) + ")";
  } else if (contenders.empty()) {
    v.reason = size +
               ": a gap, but no candidate effect is both identifiable from these observations and "
               "able to fit the calibration observations" +
               unfixed_note(candidates, order);
  } else {
    const CandidateResult& c = candidates[contenders.front().index];
    v.reason = size + ": a gap, but the best effect, " + c.candidate.effect +
               ", closes only G = " + fixed(*c.g_confirmed, 2) + " of it (< " +
               fixed(rule.min_gap_closure, 2) + "): none of the candidates explains the gap" +
               unfixed_note(candidates, order);
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
    std::vector<Contender> contenders;
    for (int i = 1; i < int(candidates.size()); ++i) {
      const CandidateResult& c = candidates[i];
      if (!eligible(c) || c.seed_ln.size() <= j) continue;
      const auto g =
          gap_closure(rms(residuals(c.seed_ln[j], lab), targets, Role::held_out), base_rms);
      if (!g) continue;
      check.gap_closure[c.candidate.effect] = *g;
      contenders.push_back({i, *g});
    }
    const int chosen = choose_effect(
        rule, rms_in_budgets(base_residuals, targets, budget, Role::held_out), contenders);
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
  return v.undetermined ? "undetermined" : verdict_label(candidates, v.candidate);
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
  if (!e.base_on_bounds.empty()) {
    std::string where;
    for (const std::string& b : e.base_on_bounds) where += (where.empty() ? "" : ", ") + b;
    causes.push_back("the base model's fit lies on the search box (" + where +
                     "): its strengths are the bounds', not the data's (widen the bounds)");
  }
  if (!causes.empty()) {
    v.undetermined = true;
    v.candidate = -1;
    v.reason = "undetermined: ";
    for (const std::string& c : causes) v.reason += c + "; ";
    v.reason += miss_text(e.base, rule.gap_budgets);
    v.miss = e.base;
    conf.level = "none";
    return;
  }
  if (misses_beyond(e.verdict, rule.gap_budgets)) {
    v.reason += "; not explained: " + miss_text(e.verdict, rule.gap_budgets);
    v.miss = e.verdict;
    // "No effect needed" denies the miss: low. A named effect explains part of it: not high.
    if (v.candidate < 0) {
      conf.level = "low";
    } else if (conf.level == "high") {
      conf.level = "medium";
    }
  }
}

}  // namespace rockcal::diagnosis
