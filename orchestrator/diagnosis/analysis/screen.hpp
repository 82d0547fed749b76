// Screening: before any effect's surfaces are run, each candidate is run at its strong value
// (s = 1) at the base model's first fit, on every condition of the dataset, and compared with the
// base model's run there (and again at the balanced point, equal strengths, where an effect that
// acts through one bond failure mode shows when the first fit lies where the other rules: the
// driver's balanced_point). The strengths' re-fit is removed linearly with the base model's local
// sensitivity (change_after_refit, as the budget's resolution term), and what is left is judged as
// identifiability judges a change: against the observation's budget + lab uncertainty. An effect
// that moves no observation beyond that, at its strongest, is invisible to these tests: whatever
// its surfaces showed would be noise, so they are not run.
#pragma once

#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "orchestrator/diagnosis/analysis/evaluator.hpp"
#include "orchestrator/diagnosis/analysis/observations.hpp"

namespace rockcal::diagnosis {

struct ScreenedEffect {
  std::string effect;
  // Per target: ln(strong / base) after the strengths' linear re-fit (NaN: a run without the
  // value).
  std::vector<double> change;
  std::vector<double> noise;           // per target: budget + lab uncertainty
  std::optional<std::size_t> largest;  // the target moved most in noise units; none measured: none
  double largest_in_noise = std::numeric_limits<double>::quiet_NaN();
  // Some target moves beyond its noise. An effect with no value to compare is kept: unknown is
  // not nothing.
  bool visible = true;
  // Where the effect's fit lies from the screen's point, in the unit cube of (ln F_r0, ln F_s0):
  // the strengths' linear re-fit of the strong run to the calibration observations, with the
  // effect's own sensitivity there (an effect can change which strength sets a peak: a random
  // packing's fail by the bonds' tension where the FCC's fail in shear). The local design centres
  // the effect's runs on it, so an effect that changes what the strengths must be is fitted where
  // its runs are, not extrapolated from the base fit's. Zero when nothing was measured.
  std::array<double, 2> fit_shift{0.0, 0.0};
  // Judged at the screen's second point (the balanced one), having no mark at the first: change,
  // largest and fit_shift are from there (fit_shift still as a shift from the first point).
  bool at_balanced = false;
};

// An effect dropped with a mark of at least this share of its noise is near the screen's threshold:
// the screen judges it where the base model fits, and data an effect raised put that fit away from
// the strengths the effect would need, where its mark can be larger (a faster platen's on a D/R 20
// UCT: +0.19 in ln at a twin's truth, +0.095 at the base fit 1.6x above it; that twin's rate,
// dropped at 0.84, was named with the screen off).
inline constexpr double kScreenNearThreshold = 0.5;

// The effects the screen dropped, for a verdict that leaves a gap unexplained: "not tried, as
// invisible to these tests (screen): a, b", and for those near the threshold their marks and how to
// design them anyway. Empty when none was dropped.
std::string screened_out_text(const std::vector<ScreenedEffect>& effects,
                              const std::vector<Target>& targets);

// The screen's runs of one effect, all at s = 1: at the screen's point, and one step along each
// strength (the effect's own sensitivity).
inline constexpr int kScreenRunsPerEffect = 3;

// One effect's mark: `strong` is its run at s = 1, `base` the base model's at the same strengths;
// jacobian and weight as StrengthResponse at that point (budget.hpp). Its fit_shift is left zero.
ScreenedEffect screen_effect(std::string effect, const RunOutcome& base, const RunOutcome& strong,
                             const std::vector<std::array<double, 2>>& jacobian,
                             const std::vector<double>& weight, const std::vector<Target>& targets,
                             const std::vector<double>& budget);

// ScreenedEffect::fit_shift: the strong run's residual to the lab values, re-fitted (refit_shift)
// on the effect's own d ln / dz there (`strong_jacobian`, NaN where a run gave no value), with the
// calibration weights.
std::array<double, 2> fit_shift(const RunOutcome& strong, const std::vector<Target>& targets,
                                const std::vector<std::array<double, 2>>& strong_jacobian,
                                const std::vector<double>& weight);

// d ln / dz per target from a run at a point and one run a step `step[d]` along each strength
// (NaN where either run has no value).
std::vector<std::array<double, 2>> secant_jacobian(const RunOutcome& at,
                                                   const std::array<RunOutcome, 2>& along,
                                                   const std::array<double, 2>& step);

}  // namespace rockcal::diagnosis
