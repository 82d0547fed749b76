// The response-surface grid: unit-cube coordinates <-> model points, the runs of every candidate's
// grid (one batch, so the pool runs them all in parallel), and the surfaces fitted to them.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "orchestrator/diagnosis/analysis/evaluator.hpp"
#include "orchestrator/diagnosis/analysis/surface_fit.hpp"
#include "orchestrator/diagnosis/pipeline/campaign.hpp"

namespace rockcal::diagnosis {

// n values spread evenly over [0, 1], ends included.
std::vector<double> grid_axis(int n);

// z = (ln F_r0, ln F_s0) mapped to [0, 1] over the bounds[, u]  ->  the model it stands for
// (u -> s through the candidate's floor).
ModelPoint model_point(const DiagnosisCampaign& c, const Candidate& candidate,
                       std::span<const double> z);

// The s levels a candidate's own grid runs: all but u = 0 when it shares the base grid.
int grid_levels(const Candidate& candidate, int s_values);
// How often the local design's star around the base fit may move to the node of the fit its runs
// gave (run_local_base), and how often an effect's design may (run_local_effects).
inline constexpr int kStarMoves = 2;
inline constexpr int kEffectMoves = 2;
// Model points of the base model's surface runs (at most, under the local design), of one effect's
// design at one place, and of every candidate's together at most (the base grid counted once; the
// local design's moves included), under the campaign's design.
int base_grid_points(const DiagnosisCampaign& c);
int effect_grid_points(const DiagnosisCampaign& c, const Candidate& effect);
int grid_points(const DiagnosisCampaign& c);
// Model points of the screen (screen.hpp) when it screens, at most: kScreenRunsPerEffect per
// candidate at each of its two points and the base model's run at the second.
int screen_model_points(const DiagnosisCampaign& c);

// The runs behind one candidate's surfaces.
struct Samples {
  std::vector<std::vector<double>> z;
  std::vector<RunOutcome> outcomes;
};

// The base grid of (ln F_r0, ln F_s0), one batch.
Samples run_base_grid(const DiagnosisCampaign& c, Evaluator& evaluator);
// Every effect's grid, one batch: per effect the base grid at each s > 0. The base grid is the
// s = 0 slice of every effect continuous at neutral (s = 0 is the base model), so it is run once
// and shared; an effect that jumps at neutral runs its own u = 0 slice. samples[0] is the base's;
// the result has one more per campaign candidate.
void run_effect_grids(const DiagnosisCampaign& c, Evaluator& evaluator,
                      std::vector<Samples>& samples);

// The base model's samples as an effect's s = 0 slice, appended to its samples.
void append_base_slice(Samples& effect, const Samples& base);
// The s = 0 slice of every effect continuous at neutral is the base model's samples: appended to
// theirs (samples[0] = the base, then one per campaign candidate).
void share_base_slice(std::vector<Samples>& samples, const DiagnosisCampaign& c);

// One response surface per target through the successful runs.
SurfaceSet fit_surfaces(const Samples& samples, int dims, std::size_t targets);

// A model calibrated on its surfaces with lab uncertainties alone (before the budget is known):
// for the base, where the budget is measured first; for every model, where the local design
// centres its runs. nullopt when no calibration observation has a surface (the runs failed).
std::optional<SurfaceCalibration> fit_on_lab(const DiagnosisCampaign& c,
                                             const SurfaceSet& surfaces);

}  // namespace rockcal::diagnosis
