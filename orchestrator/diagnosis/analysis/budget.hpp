// The numerical error budget: how much each observation moves when nothing physical changes (other
// packing seeds, half the platen speed, a finer resolution). A residual inside it is not a physics
// gap, and an effect that moves nothing beyond it cannot be told apart from numerical noise.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "orchestrator/diagnosis/analysis/evaluator.hpp"
#include "orchestrator/diagnosis/analysis/observations.hpp"
#include "orchestrator/diagnosis/analysis/surface_fit.hpp"
#include "orchestrator/diagnosis/dataset/dataset.hpp"

namespace rockcal::diagnosis {

struct BudgetSpec {
  std::vector<std::uint64_t> seeds;  // replicate packing seeds (default: template seed + 1, + 2)
  double speed_factor = 0.5;         // platen speed multiplier
  // Particles-per-length multipliers. On a coarse FCC packing each refinement is one draw of which
  // lattice rows the specimen keeps (docs/diagnosis.md, "The error budget"), so several give a
  // truer spread than one; the default is a single 1.25x.
  std::vector<double> resolutions{1.25};
  // Model points the variants are run at: the base fit and its neighbours (budget_offsets). One
  // point gives one draw of a change that on a coarse packing jumps by x4 between neighbouring
  // strengths; the rms over several is the spread the budget stands for.
  int points = 5;
};

struct BudgetVariant {
  std::string name;  // "seed 2", "speed x0.5", "resolution x1.25"
  Numerics numerics;
  // Variants of one kind ("seed", "speed", "resolution") are draws of one source of numerical
  // error and pool by rms; kinds count by the largest.
  std::string kind;
};

// One source of numerical error and whether it separates a dataset's numbers from the model's
// runs. Charging data an error they do not carry hides real gaps: a twin made by the model itself
// at its own resolution and speed shares the model's lattice cut and rate error, so only the draws
// of its specimen (the seed) differ; lab data and a finer model's numbers carry all three.
struct ErrorTerm {
  std::string kind;  // "seed", "speed", "resolution": a BudgetVariant kind
  bool applies;
  std::string why;
};
std::vector<ErrorTerm> error_terms(Origin origin);

// The seed replicates first, then the speed and the resolution variants; only the kinds that
// apply to data of this origin.
std::vector<BudgetVariant> budget_variants(const BudgetSpec& spec, std::uint64_t template_seed,
                                           Origin origin = Origin::lab);
// Runs at each budget point: the reference and every variant.
std::size_t budget_runs_per_point(const BudgetSpec& spec, Origin origin = Origin::lab);

// Unit-cube offsets (fr0, fs0) of the budget's points from the base fit: the fit itself, then
// +-kBudgetStep along each strength, then the diagonals; the first `points` of them.
inline constexpr double kBudgetStep = 0.1;  // of the log box: x1.32 on the default bounds
std::vector<std::vector<double>> budget_offsets(int points);
// The budget's points around the unit-cube fit z: z + each offset, clamped to the cube, each once
// (a fit on the edge of the box would otherwise count its own point twice).
std::vector<std::vector<double>> budget_points(const std::vector<double>& z, int points);

struct Budget {
  std::vector<BudgetVariant> variants;
  std::vector<std::vector<double>> change;  // [variant][target] rms over points of |ln change|, NaN
  std::vector<bool> refitted;               // [variant]: the change left after a re-fit (below)
  std::vector<double> per_target;           // the largest change; see numerical_budget
  std::vector<bool> measured;               // false where no variant measured the target
  int points = 0;                           // model points the changes were averaged over
};

// A finer resolution moves every observation of a bonded model together (the peaks fall or rise
// with the lattice cut and the bond count per area), and the strengths are calibrated on the data:
// the part of that move which re-fitting them absorbs is a bias shared by calibration and held-out
// observations, not an error of a calibrated model's prediction. What a calibrated model carries is
// the rest, the move's component the strengths cannot follow. To measure it the budget re-fits the
// strengths to the refined run's calibration values, linearly: jacobian[p][i] is d ln(target i) /
// d(unit-cube F_r0, F_s0) of the base model at budget point p, weight[i] the target's calibration
// weight (1 / sigma^2; 0 for held out).
struct StrengthResponse {
  std::vector<std::vector<std::array<double, 2>>> jacobian;  // [point][target]
  std::vector<double> weight;                                // [target]
};

// A target's weight in the strengths' re-fit as a calibration observation: 1 / sigma^2 (the lab
// uncertainty alone: the budget is what is being measured), sigma at least kMinNoiseScale.
double refit_weight(const Target& target);

// The base model's StrengthResponse at each unit-cube point, from its surfaces (central
// differences, one-sided at a face of the cube), with the targets' calibration weights.
StrengthResponse strength_response(const SurfaceSet& base, const std::vector<Target>& targets,
                                   const std::vector<std::vector<double>>& points);

// The strengths' best linear re-fit to the calibration targets' changes: the unit-cube dz of
// min sum_i w_i (change_i - J_i dz)^2 (NaN changes left out; the minimum-norm dz along the one
// direction the targets see when they see one).
std::array<double, 2> refit_shift(const std::vector<double>& change,
                                  const std::vector<std::array<double, 2>>& jacobian,
                                  const std::vector<double>& weight);

// The change of each target left after that re-fit (NaN changes stay NaN).
std::vector<double> change_after_refit(const std::vector<double>& change,
                                       const std::vector<std::array<double, 2>>& jacobian,
                                       const std::vector<double>& weight);

// Per variant and target the rms over the points of |ln(variant / reference)|; per kind the rms
// over its variants; per target the largest over the kinds. outcomes[p][v] is variant v at point p,
// references[p] the point's nominal run. With `response`, a resolution variant's change at each
// point is first reduced to what re-fitting the strengths leaves (StrengthResponse). A target no
// variant measured (every run failed) gets the largest budget of the others: unknown noise is not
// counted as no noise.
Budget numerical_budget(std::vector<BudgetVariant> variants,
                        const std::vector<RunOutcome>& references,
                        const std::vector<std::vector<RunOutcome>>& outcomes,
                        const StrengthResponse* response = nullptr);

}  // namespace rockcal::diagnosis
