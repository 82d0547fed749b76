#include "orchestrator/diagnosis/pipeline/next_test_runs.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "orchestrator/diagnosis/analysis/gap.hpp"
#include "orchestrator/diagnosis/analysis/identifiability.hpp"
#include "orchestrator/diagnosis/analysis/screen.hpp"
#include "orchestrator/diagnosis/pipeline/grid.hpp"
#include "orchestrator/diagnosis/pipeline/local_design.hpp"

namespace rockcal::diagnosis {
namespace {

const Candidate* find_candidate(const DiagnosisCampaign& c, const std::string& effect) {
  for (const Candidate& k : c.candidates) {
    if (k.effect == effect) return &k;
  }
  return nullptr;
}

// Why the calibration observations cannot identify an effect; "" when they can (or it was never
// judged: a kept effect that could not be fitted).
std::string unidentified(const std::string& effect, const DiagnosisResult& r,
                         const DiagnosisCampaign& c) {
  for (const ScreenedEffect& e : r.screen.effects) {
    if (e.effect == effect && !e.visible) {
      return "invisible to the dataset's tests (screen): it moves no observation beyond its noise";
    }
  }
  if (!judges_effects(c)) {
    return "not judged: the dataset has no held-out observation, so no evidence can tell it from "
           "the base model";
  }
  const std::vector<Target>& targets = c.targets;
  for (const CandidateResult& k : r.candidates) {
    if (k.candidate.effect != effect || !k.identifiability || k.identifiability->identifiable) {
      continue;
    }
    return identifiability_reason(*k.identifiability, targets);
  }
  return "";
}

// The base model at `z` and one step along each strength (backwards at the box's upper face),
// appended to `runs`; the steps.
std::array<double, 2> add_base_runs(const DiagnosisCampaign& c, const std::vector<double>& z,
                                    const Numerics& numerics, std::vector<RunRequest>& runs) {
  std::array<double, 2> step{};
  runs.push_back({model_point(c, Candidate{}, z), numerics});
  for (std::size_t d = 0; d < 2; ++d) {
    std::vector<double> at = z;
    step[d] = at[d] + kBudgetStep <= 1.0 ? kBudgetStep : -kBudgetStep;
    at[d] += step[d];
    runs.push_back({model_point(c, Candidate{}, at), numerics});
  }
  return step;
}

bool screened_at_balanced(const ScreenResult& screen, const std::string& effect) {
  for (const ScreenedEffect& e : screen.effects) {
    if (e.effect == effect) return e.at_balanced;
  }
  return false;
}

}  // namespace

int next_test_model_points(const DiagnosisCampaign& campaign) {
  if (campaign.candidates.empty()) return 0;  // nothing to tell apart
  // The base's runs at the fit, and at the screen's balanced point for effects seen only there.
  const std::size_t base = campaign.screen ? 2 * kNextTestBaseRuns : kNextTestBaseRuns;
  const std::size_t variants =
      budget_variants(campaign.budget, campaign.sample_seed, campaign.dataset.origin).size();
  return int(base + campaign.candidates.size() + variants);
}

NextTest run_next_test(const DiagnosisCampaign& c, const DiagnosisResult& r, Evaluator& evaluator) {
  NextTest out;
  out.enabled = true;
  out.menu = test_menu(c.targets);
  if (out.menu.empty()) {
    out.reason = "the dataset already has every test on the menu";
    return out;
  }
  const std::vector<double>& budget = r.budget.per_target;
  for (MenuTest& m : out.menu) {
    out.noise.push_back(borrowed_noise(m.target, c.targets, budget));
    m.target.sigma = out.noise.back().sigma;
  }
  const std::vector<Target> all = with_menu(c.targets, out.menu);

  // The two leading hypotheses: the verdict and the runner-up, or without a verdict the runner-up
  // (the best-ranked effect) and the base model.
  const int a = r.verdict.candidate >= 0 ? r.verdict.candidate : r.verdict.runner_up;
  const int b = r.verdict.candidate >= 0 ? r.verdict.runner_up : -1;
  auto name = [&](int k) { return k > 0 ? r.candidates[k].candidate.effect : std::string(); };
  std::vector<std::string> why;
  for (const Candidate& k : c.candidates) {
    const std::string reason = unidentified(k.effect, r, c);
    const bool leading = (a > 0 && k.effect == name(a)) || (b > 0 && k.effect == name(b));
    if (!leading && reason.empty()) continue;
    out.effects.push_back(k.effect);
    why.push_back(reason);
  }
  if (a <= 0 && out.effects.empty()) {
    out.reason = "no effect to tell apart: none was tried";
    return out;
  }

  // The base at its fit and one step along each strength (backwards at the box's upper face); in
  // the local design at the fit's lattice node, so that datasets on one template share the runs.
  // An effect the screen saw only at its balanced point (screen.hpp) is marked there, against the
  // base's runs there (after the effects' runs).
  const std::vector<double> z = study_point(c, r.candidates[0].calibration.z);
  const Numerics nominal{c.sample_seed, 1.0, 1.0};
  out.point = model_point(c, Candidate{}, z);
  const std::array<double, 2> step = add_base_runs(c, z, nominal, out.runs);
  std::vector<bool> balanced;
  for (const std::string& effect : out.effects) {
    balanced.push_back(screened_at_balanced(r.screen, effect));
    const std::vector<double>& at = balanced.back() ? r.screen.balanced_z : z;
    out.runs.push_back(
        {model_point(c, *find_candidate(c, effect), std::vector<double>{at[0], at[1], 1.0}),
         nominal});
  }
  const std::size_t balanced_base = out.runs.size();
  std::array<double, 2> balanced_step{};
  const bool any_balanced = std::find(balanced.begin(), balanced.end(), true) != balanced.end();
  if (any_balanced) {
    balanced_step = add_base_runs(c, r.screen.balanced_z, nominal, out.runs);
  }
  // The menu's budgets: the base at the fit under each of the budget's variants.
  const std::vector<BudgetVariant> variants =
      budget_variants(c.budget, c.sample_seed, c.dataset.origin);
  const std::size_t variants_first = out.runs.size();
  for (const BudgetVariant& v : variants) out.runs.push_back({out.point, v.numerics});
  const std::vector<RunOutcome> outcomes = evaluator.run_on(out.runs, all);
  out.model_points = int(out.runs.size());
  const std::size_t n = c.targets.size();
  for (const RunOutcome& o : outcomes) {
    const std::vector<double> ln = ln_values(o);
    out.ln.emplace_back(ln.begin() + long(n), ln.end());
  }

  // How each test follows the strengths at a point whose base runs start at `first`: the dataset's
  // on the base surfaces (as the screen), the menu's from the two steps.
  auto response_at = [&](std::size_t first, const std::vector<double>& at,
                         const std::array<double, 2>& steps) {
    StrengthResponse response = strength_response(r.candidates[0].surfaces, c.targets, {at});
    for (std::size_t m = 0; m < out.menu.size(); ++m) {
      std::array<double, 2> slope{};
      for (std::size_t d = 0; d < 2; ++d)
        slope[d] = (out.ln[first + 1 + d][m] - out.ln[first][m]) / steps[d];
      response.jacobian[0].push_back(slope);
      response.weight.push_back(0.0);
    }
    return response;
  };
  const StrengthResponse at_fit = response_at(0, z, step);
  const StrengthResponse at_balanced =
      any_balanced ? response_at(balanced_base, r.screen.balanced_z, balanced_step) : at_fit;
  const std::vector<RunOutcome> changed(outcomes.begin() + long(variants_first), outcomes.end());
  use_measured_budgets(out.noise, numerical_budget(variants, {outcomes[0]}, {changed}, &at_fit), n);
  for (std::size_t e = 0; e < out.effects.size(); ++e) {
    const StrengthResponse& response = balanced[e] ? at_balanced : at_fit;
    const std::vector<double> base = ln_values(outcomes[balanced[e] ? balanced_base : 0]);
    const std::vector<double> strong = ln_values(outcomes[run_of(out, out.effects[e])]);
    std::vector<double> change(base.size());
    for (std::size_t i = 0; i < base.size(); ++i) change[i] = strong[i] - base[i];
    out.mark.push_back(joined_marks(change, response.jacobian[0], response.weight, all, n));
  }
  if (a > 0) {
    out.leading =
        separate(name(a), name(b), mark_of(out, name(a)), mark_of(out, name(b)), out.noise);
  }
  for (std::size_t e = 0; e < out.effects.size(); ++e) {
    if (why[e].empty()) continue;
    Separation s = separate(out.effects[e], "", out.mark[e], {}, out.noise);
    s.why = why[e];
    out.invisible.push_back(std::move(s));
  }
  return out;
}

}  // namespace rockcal::diagnosis
