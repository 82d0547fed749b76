// The evidence that ranks the candidates: how probable each model makes the held-out observations
// (the held-out log predictive density), and how much more probable than the base model does.
// Each held-out charged residual r_i = ln(sim / lab) (gap.hpp) is read as a draw from
// N(0, v_i), v_i = budget_i^2 + sigma_i^2 (the observation's numerical budget and lab uncertainty),
// plus the spread the candidate's fit leaves in its prediction (fit_spread.hpp) and the emulator's
// variance at its fitted point when its prediction comes from its surfaces and not from real runs
// (surface.hpp): the posterior predictive of a held-out observation, not of a point estimate.
// lpd = sum_i -0.5 (r_i^2 / v_i + ln(2 pi v_i)), in nats.
// An effect's evidence is its lpd minus the base model's over the held-out observations both
// predict: a log Bayes factor on held-out data, where the effect's parameter was fitted on the
// calibration observations only. Each candidate carries its own (CandidateResult::density,
// evidence; mark_evidence in verdict.hpp).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "orchestrator/diagnosis/analysis/observations.hpp"

namespace rockcal::diagnosis {

// One held-out observation's share of the density.
struct DensityTerm {
  std::size_t target = 0;            // index into the targets
  double residual = 0.0;             // charged ln(sim / lab)
  double variance = 0.0;             // v_i, at least kMinNoiseScale^2
  double prediction_variance = 0.0;  // its share from the prediction (fit spread, emulator)
  double lpd = 0.0;                  // -0.5 (r_i^2 / v_i + ln(2 pi v_i))
};

struct HeldOutDensity {
  double lpd = 0.0;  // the sum of the terms
  std::vector<DensityTerm> terms;
};

// Over the held-out targets whose residual is finite (residuals: ln(sim / lab), NaN where a run
// gave no value; charged here, as every rms is). `prediction_variance` per target adds to v_i;
// empty adds nothing, and a NaN entry (no surface for the target) leaves that target out.
HeldOutDensity held_out_density(const std::vector<double>& residuals,
                                const std::vector<Target>& targets,
                                const std::vector<double>& budget,
                                const std::vector<double>& prediction_variance = {});

// The model's lpd minus the base's over the targets both have a term for; nullopt without one.
std::optional<double> evidence_over(const HeldOutDensity& model, const HeldOutDensity& base);

}  // namespace rockcal::diagnosis
