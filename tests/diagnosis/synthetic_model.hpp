// A formula "engine" for the diagnosis's unit tests: closed-form observables of the twin design in
// which each hidden effect leaves its own signature, and numerics that move values by about 1%,
// so the whole algorithm runs in milliseconds.
// An effect's parameter is fitted on the calibration observations, so each effect leaves a mark
// there that the bond strengths cannot absorb (on the modulus or the triaxial gain; two strengths
// absorb any change of the UCT and BTT peaks), and a different one on the held-out observations:
//   size        the modulus falls, and strength falls with specimen size (a Weibull-like size
//               effect): the 1.5x specimens
//   confinement the triaxial gain grows with s: the two confinements move differently
//   rate        the modulus rises, and peaks rise faster with platen speed: the fast UCT
//   uniform     every peak falls by the same factor: the bond strengths absorb it (not
//               identifiable)
//   modulus     only the UCT's Young's modulus moves, as under size: it fits the calibration
//               observations as well as size does and predicts nothing held out
// Besides these, `marks` can hold the engine's registered effects as they were measured
// (measured_marks): per observation of the real twin design, the change of ln(value) at s = 1 with
// the strengths re-fitted, applied as s x mark to every run under that observation's conditions
// (mark_of: a test the design does not have takes the mark of the one it was measured as).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "orchestrator/diagnosis/analysis/evaluator.hpp"
#include "orchestrator/diagnosis/pipeline/campaign.hpp"

namespace rockcal::diagnosis::testing {

// The twin design on a D = 10, H = 20 template at 0.05 m/s: calibration UCT peak and modulus, BTT
// peak, triaxial at p1; held out triaxial at p2, UCT and BTT at 1.5 D, UCT at 4x speed.
std::vector<Target> twin_targets();

std::vector<Candidate> synthetic_candidates();  // size, confinement, rate, uniform, modulus

// effect -> target id -> change of ln(value) at s = 1 (0 where absent).
using Marks = std::map<std::string, std::map<std::string, double>>;

// The registered effects' marks on the real twin design (registry_twin_campaign) at their
// "strong" value, from the signature table of docs/effects.md (D/R 20, 3 seeds, the strengths
// re-fitted to the UCS and BTS): the cells beyond 2 standard errors on an observable the effect can
// reach (packing's H/D = 1 cell has no standard error and is left out). The calibration peaks
// carry none: the re-fit absorbed them.
Marks measured_marks();

// Where a registered effect's change begins on the default template (its first_change_of, as a
// walk fraction; 0 when it has none): interaction_range in FCC bonds nothing new below sqrt(2),
// so its mark is a step there, not a ramp from s = 0.
double first_change_s(const std::string& effect);
// Where a twin asked for `effect` at s hides it: s, or its first change when s lies below it.
double hidden_s(const std::string& effect, double s);
// The share of a measured mark (taken at s = 1) a run at walk fraction s carries: s, or for an
// effect with a first change 1 from it on and 0 below.
double mark_share(const std::string& effect, double s);

struct SyntheticModel : Evaluator {
  std::vector<Target> targets;
  double numerical_noise = 0.005;  // seed-to-seed scatter, relative
  int runs = 0;                    // model points run
  Marks marks;                     // effects beyond the formula ones (measured_marks)

  explicit SyntheticModel(std::vector<Target> t) : targets(std::move(t)) {}
  std::vector<double> values(const RunRequest& r) const;  // on `targets`
  std::vector<double> values(const RunRequest& r, const std::vector<Target>& on) const;
  std::vector<RunOutcome> run_batch(std::span<const RunRequest> requests) override;
  std::vector<RunOutcome> run_on(std::span<const RunRequest> requests,
                                 const std::vector<Target>& on) override;
};

// A campaign whose lab values are the model's at (fr0, fs0) = (60, 120) with `effect` at `s`
// ("" = none), times lab noise exp(noise x N(0,1)) drawn from `seed`, uncertainty 2%.
DiagnosisCampaign twin_campaign(const std::string& effect, double s, double noise = 0.01,
                                std::uint64_t seed = 7);

// The same twin on the real twin design (the UCT at H/D = 1 for the 1.5x cylinder, the UCT's peak
// strain held out), whose candidates are the engine's registered effects (registry_candidates)
// leaving measured_marks. An effect hidden below its first change would be the base model again:
// it is hidden at hidden_s(effect, s).
DiagnosisCampaign registry_twin_campaign(const std::string& effect, double s, double noise = 0.01,
                                         std::uint64_t seed = 7);

}  // namespace rockcal::diagnosis::testing
