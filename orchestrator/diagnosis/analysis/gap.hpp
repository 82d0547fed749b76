// Residuals and the numbers built on them: rms by role, the noise scale of each observation
// (budget and lab uncertainty) and the gap closure G.
#pragma once

#include <optional>
#include <vector>

#include "orchestrator/diagnosis/analysis/evaluator.hpp"
#include "orchestrator/diagnosis/analysis/observations.hpp"

namespace rockcal::diagnosis {

// ln of every value of a run; NaN where it has none.
std::vector<double> ln_values(const RunOutcome& outcome);
std::vector<double> ln_lab(const std::vector<Target>& targets);

// ln(sim / lab) per target (NaN where sim is NaN).
std::vector<double> residuals(const std::vector<double>& ln_sim, const std::vector<double>& ln_lab);

// The part of each residual the model is charged with: zero inside the span of values the data
// themselves give under the same conditions (data_spans, consistency.hpp), the distance to the
// nearer end of it outside; the residual itself for a target in no inconsistent pair. rms and
// rms_in_budgets judge these, so a pair's disagreement is never a gap of the model.
std::vector<double> charged_residuals(const std::vector<double>& residuals,
                                      const std::vector<Target>& targets);

// rms over the targets of one role with a finite residual, charged (charged_residuals); nullopt
// when there are none.
std::optional<double> rms(const std::vector<double>& residuals, const std::vector<Target>& targets,
                          Role role);

// sqrt(budget^2 + sigma^2 + fit_variance): the spread a residual of one target has without any
// physics gap; fit_variance is the spread the calibration leaves in a held-out prediction
// (fit_spread.hpp), 0 for a calibration observation.
double noise_scale(const Target& target, double budget, double fit_variance = 0.0);
// The least noise scale a residual is divided by (0.1%), so that an exact lab value with no
// budget neither takes all of a calibration's weight nor makes a gap infinite.
inline constexpr double kMinNoiseScale = 1e-3;

// sqrt(mean over the role of noise_scale^2): what the rms of that role's residuals would be from
// numerical noise and lab scatter alone (reported beside the rms; the verdict uses
// rms_in_budgets).
double combined_budget(const std::vector<Target>& targets, const std::vector<double>& budget,
                       Role role);

// sqrt(mean over the role's targets with a finite residual of (charged residual / noise_scale)^2):
// the residuals each in units of its own observation's noise, the fit's spread in it where
// `fit_variance` gives one (empty: none). The verdict calls a held-out gap only
// above 1. Budgets differ by x10 between observations (on the 117-particle demo twins the 1.5x
// UCT's has a median of 0.64 in ln, the 1.5x BTT's 0.21), and a pooled rms against the pooled
// budget lets the noisy observation hide a gap the precise one shows. nullopt when there are none.
std::optional<double> rms_in_budgets(const std::vector<double>& residuals,
                                     const std::vector<Target>& targets,
                                     const std::vector<double>& budget, Role role,
                                     const std::vector<double>& fit_variance = {});

// G = 1 - rms(held-out, effect) / rms(held-out, base); nullopt when either is missing or the base
// has no gap at all.
std::optional<double> gap_closure(std::optional<double> rms_effect, std::optional<double> rms_base);

// The share of the held-out gap beyond noise that an effect closes, from the two models' held-out
// rms in noise units (rms_in_budgets, the fit's spread included): pure noise has a mean square of
// 1 there, so the gap is the mean square beyond it, and
//   G_noise = 1 - sqrt(max(b_effect^2 - 1, 0)) / sqrt(b_base^2 - 1).
// G above counts the noise as gap: an effect that leaves only noise behind closes 1 - 1/b_base of
// it (0.49 at a 1.95-budget gap), G_noise all of it. nullopt when either is missing or the base's
// held-out residuals lie within their noise (no gap beyond it to close).
std::optional<double> gap_closure_beyond_noise(std::optional<double> effect_budgets,
                                               std::optional<double> base_budgets);

}  // namespace rockcal::diagnosis
