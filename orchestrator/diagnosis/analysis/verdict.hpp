// Ranking, the verdict rule and its replay under replicate packing seeds.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "orchestrator/diagnosis/analysis/candidate_result.hpp"
#include "orchestrator/diagnosis/analysis/miss.hpp"
#include "orchestrator/diagnosis/analysis/observations.hpp"

namespace rockcal::diagnosis {

// The verdict under one replicate packing seed: base and confirmed candidates re-run at their
// fitted points on that packing.
struct SeedCheck {
  std::uint64_t seed = 0;
  std::string verdict;  // effect name, or "" for no effect needed
  std::map<std::string, double> gap_closure;
  std::map<std::string, double> evidence;  // nats over the base on this seed's runs
  // False when every re-run equals its nominal run: a regular packing with no seeded effect does
  // not depend on the seed, and the check then repeats the verdict instead of testing it.
  bool informative = true;
};

struct Confidence {
  int replicates = 0;                  // bootstrap replicates
  double agreement = 0.0;              // share of them with the nominal verdict
  std::map<std::string, int> winners;  // verdict ("" = none) -> replicates
  std::vector<SeedCheck> seeds;
  int seeds_informative = 0;  // of `seeds`; only these count
  int seeds_agreeing = 0;     // informative seeds that reach the nominal verdict
  std::string level;          // high | medium | low
};

struct Verdict {
  int candidate = -1;  // index into candidates; -1 = no effect needed
  int best = -1;       // the contender with the most evidence, named or not; -1 = none
  int runner_up = -1;
  bool undetermined = false;  // the data cannot judge any effect (temper_verdict)
  std::string reason;
  std::optional<ModelMiss> miss;  // the miss the reason states (temper_verdict), if any
  // When the base model's fit lies on the search box: whether the bound holds it (temper_verdict).
  struct Bound {
    std::vector<std::string> on;        // on_bounds of the base fit
    std::optional<double> calibration;  // its calibration miss there, rms in noise budgets
    std::optional<double> refitted;     // the same with its strengths re-fitted beyond
    bool holds = true;                  // the bound may be what the miss is
  };
  std::optional<Bound> bound;
};

// The verdict rule (docs/diagnosis.md, "Verdict rules"). An effect is named when its evidence
// over the base model (held-out log predictive density, evidence.hpp) exceeds min_evidence. The
// default is calibrated on null twins of the formula engine
// (tests/diagnosis/evidence_twin_test.cpp: at most 10% of them put a contender above it);
// bench/diagnosis_confusion.py prints the same threshold from the null twins of a campaign's own
// template. gap_budgets is where a residual stops being noise: the report's gap test and the miss a
// verdict states (temper_verdict).
struct DecisionRule {
  double gap_budgets = 1.0;   // held-out rms, in noise budgets, above which the report calls a gap
  double min_evidence = 1.0;  // nats over the base model that name an effect
};

struct Contender {
  int index;        // into the candidates
  double evidence;  // nats over the base model
};

// The base model leaves a gap to explain: its held-out rms in noise budgets (`held_out_budgets`;
// none: no held-out residual) above rule.gap_budgets. Within them it meets the held-out data to
// their noise, and what evidence an effect gains there is that noise's (a compression-coupling
// twin at D/R 20 whose base left 0.997 budgets named rate at 1.41 nats).
bool leaves_gap(const DecisionRule& rule, std::optional<double> held_out_budgets);

// The contender with the most evidence if it exceeds rule.min_evidence and the base model leaves a
// gap (leaves_gap); otherwise -1 ("no effect needed"). Ties keep the earlier.
int choose_effect(const DecisionRule& rule, const std::vector<Contender>& contenders,
                  std::optional<double> held_out_budgets);

// A candidate explains the data only if it fits the calibration observations: its calibration rms
// (real runs if confirmed, else surfaces) must lie within the combined calibration budget of the
// best candidate's, or within kCalibrationFitBudgets of those budgets. Held-out data rank the
// candidates; this only keeps out those whose good held-out prediction comes with calibration
// residuals many noise levels wide. Generous on purpose: one odd calibration value (a lab
// modulus off by 15%) leaves the right effect at about 3 budgets, and it must stay eligible.
inline constexpr double kCalibrationFitBudgets = 4.0;

// A base fit on the search box is held by the bound only if moving past it would lower its
// calibration miss by more than this (rms, noise budgets): a smaller gain is within the noise of
// the miss itself, the data barely depending on the bounded strength there (a rate twin's fit runs
// to F_r0's bound where shear governs every peak), so the bound's value is arbitrary, not limiting.
inline constexpr double kBoundGainBudgets = 0.25;
void mark_calibration_fits(std::vector<CandidateResult>& candidates, double combined_calibration);

// Every fitted candidate's held-out density from its real runs if confirmed, else from its
// surfaces with their emulator variance added (none without a term); each effect's evidence
// over the (confirmed) base.
void mark_evidence(std::vector<CandidateResult>& candidates, const std::vector<Target>& targets,
                   const std::vector<double>& ln_lab, const std::vector<double>& budget);

// A confirmed effect whose real runs miss the held-out observations by more than the base model's
// (G <= 0): whatever evidence it has comes from the width of its prediction (the spread a loosely
// fixed parameter leaves, fit_spread.hpp), not from a closer one; a vaguer model outscores a base
// that misses by several noise units (docs/diagnosis-measurements.md, the Zigong sandstone). Never
// named, in the verdict, the seed checks or the bootstrap.
bool wider_not_closer(const CandidateResult& c);

// The variance a candidate's prediction adds to each held-out observation's: the spread its fit
// leaves (fit_spread.hpp, from its surfaces; none without them), plus, when the prediction comes
// from the surfaces and not from real runs (not confirmed), each surface's emulator variance at
// the fitted point (NaN without one: the target is not scored).
std::vector<double> predictive_variance(const CandidateResult& c,
                                        const std::vector<Target>& targets,
                                        const std::vector<double>& budget);

// The fit's spread in each held-out prediction of a candidate's real runs (fit_spread.hpp), 0 on
// the calibration observations (the fit's own residuals there are no wider than their noise): what
// the gap test and the stated miss (model_miss) add to each observation's noise.
std::vector<double> held_out_fit_variance(const CandidateResult& c,
                                          const std::vector<Target>& targets,
                                          const std::vector<double>& budget);

// Ranks the effects (candidates[1..]) and sets their `rank` (1 = best): confirmed identifiable
// ones that fit the calibration by their evidence (real runs), then the other identifiable ones
// that fit by their evidence on the surfaces, then identifiable ones that do not fit the
// calibration observations, then the non-identifiable ones, then those that could not be fitted;
// by evidence within each, those without any (surfaces too thin for a leave-one-out error, as the
// local design's effects) after those with, by G. Returns the indices in rank order.
std::vector<int> rank_effects(std::vector<CandidateResult>& candidates);

// The verdict over the confirmed identifiable effects that fit the calibration (real runs only,
// by evidence) and the runner-up (the best-ranked effect that is not the verdict), with a
// sentence saying why. `gap` is the base's held-out residuals in budgets (rms_in_budgets of its
// real runs), quoted with the combined budget.
Verdict decide(const DecisionRule& rule, const std::vector<CandidateResult>& candidates,
               const std::vector<int>& order, std::optional<double> gap, double combined_held_out);

// The verdict rule replayed on each replicate seed's runs of the base and confirmed effects (their
// evidence from those runs); a seed is informative when some candidate's runs on it differ from
// its nominal runs.
std::vector<SeedCheck> seed_checks(const DecisionRule& rule,
                                   const std::vector<CandidateResult>& candidates,
                                   const std::vector<Target>& targets,
                                   const std::vector<std::uint64_t>& seeds,
                                   const std::vector<double>& budget);

// high: >= 90% of bootstrap replicates and every informative seed agree; medium: >= 70% and
// most informative seeds; low otherwise.
std::string confidence_level(const Confidence& c);

// "heterogeneity", or "no effect needed".
std::string verdict_label(const std::vector<CandidateResult>& candidates, int index);
// The verdict's label: "undetermined" when it is; "unexplained miss" when no effect is named and
// the reason states a miss (temper_verdict, 2.); else verdict_label.
std::string verdict_label(const std::vector<CandidateResult>& candidates, const Verdict& v);

// The fitted coordinates (unit cube: F_r0, F_s0, s) that sit on the search box ("fr0 lower",
// "s upper"): there the fit is the bound, not an optimum.
std::vector<std::string> on_bounds(const std::vector<double>& z);

// What the data let the verdict say (docs/diagnosis.md, "Verdict rules"), applied to the rule's
// verdict and confidence last, so that no later step can make them surer:
// 1. Undetermined when no effect can be judged: nothing is held out; the base model has no
//    held-out residual (its runs failed); or the base model's fit lies on the search box and the
//    bound holds it (its strengths are the bounds', not the data's): unless, re-fitted beyond the
//    box linearly on its sensitivity there, its calibration miss stays above
//    kCalibrationFitBudgets, which no strengths then remove (a random packing's twin on the FCC
//    model misses its modulus); the reason then says so and the verdict goes on. Undetermined
//    means the label "undetermined" (never "no effect needed"), no effect named, confidence
//    "none", and a reason that names every cause and states the base model's miss observation by
//    observation (miss_text).
// 2. An unexplained miss: the verdict's model (the named effect's real runs, or the base
//    model's) misses its calibration or its held-out observations by more than the rule's
//    gap_budgets (rms in noise budgets). Then the confidence is never "high": "low" with no
//    effect named (labelled "unexplained miss", never "no effect needed", which would deny it),
//    at most "medium" beside a named effect (it explains part of it); the reason adds the miss.
// The miss quoted is kept in Verdict::miss, so the report carries every figure of the sentence.
struct Evidence {
  int held_out_observations = 0;
  bool base_has_held_out = false;
  std::vector<std::string> base_on_bounds;
  // The base model's calibration rms in noise budgets with its strengths re-fitted without the box,
  // linearly on its surfaces' sensitivity at its fit (nullopt: not measured).
  std::optional<double> base_calibration_refitted;
  ModelMiss base;     // the base model's real residuals (model_miss)
  ModelMiss verdict;  // the verdict's model: the named effect's, else the base model's
};
void temper_verdict(const DecisionRule& rule, const Evidence& evidence, Verdict& verdict,
                    Confidence& confidence);

}  // namespace rockcal::diagnosis
