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
// Model points of every candidate's surfaces together, under the campaign's design (the base grid
// counted once).
int grid_points(const DiagnosisCampaign& c);

// The runs behind one candidate's surfaces.
struct Samples {
  std::vector<std::vector<double>> z;
  std::vector<RunOutcome> outcomes;
};

// Runs every grid in one batch: the base grid of (ln F_r0, ln F_s0), and per effect the same grid
// at each s > 0. The base grid is the s = 0 slice of every effect continuous at neutral (s = 0 is
// the base model), so it is run once and shared; an effect that jumps at neutral runs its own
// u = 0 slice. Result: [0] = base, then one per campaign candidate.
std::vector<Samples> run_grids(const DiagnosisCampaign& c, Evaluator& evaluator);

// The s = 0 slice of every effect continuous at neutral is the base model's samples: appended to
// theirs (samples[0] = the base, then one per campaign candidate).
void share_base_slice(std::vector<Samples>& samples, const DiagnosisCampaign& c);

// One response surface per target through the successful runs.
SurfaceSet fit_surfaces(const Samples& samples, int dims, std::size_t targets);

// The base model calibrated on its surfaces with lab uncertainties alone (before the budget is
// known): where the budget is measured first, and where the local design centres its runs.
// nullopt when no calibration observation has a surface (the base runs failed).
std::optional<SurfaceCalibration> fit_base_on_lab(const DiagnosisCampaign& c,
                                                  const SurfaceSet& base);

}  // namespace rockcal::diagnosis
