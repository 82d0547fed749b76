// The local design (grid.design = "local"): runs where the calibration will look, not over the
// whole strength box. A global grid spends 25 runs per s level on every effect, nearly all far from
// any fit the lab data allow; that cost is what kept specimens at toy sizes. Here the base model's
// coarse grid locates its fit, a star around that fit refines it, and each effect then runs only at
// the refined fit: its s levels there, plus two arms at s = 1 that measure how the effect changes
// the strengths' leverage. With the base model's runs as every effect's s = 0 slice, that is the
// least a full quadratic in (ln F_r0, ln F_s0, s) needs: 4 runs per effect instead of 50 on a
// 5 x 5 x 3 grid (an effect that jumps at neutral has no base slice: 5 per level and a corner). The
// surfaces are then exact near the fit and extrapolate beyond it; the confirmation's real runs
// (driver.cpp) correct them where the candidates' fits land.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "orchestrator/diagnosis/pipeline/grid.hpp"

namespace rockcal::diagnosis {

// The node of the lattice of spacing h nearest z (its strength coordinates), kept one step inside
// the unit square. The local design runs on this lattice, not at the fit itself: fits of different
// datasets on one template (twins, a lab's repeat) that round to one node ask for the same runs,
// which the job store then answers once. The surfaces are quadratics through the node's star, so a
// fit up to h / 2 from it is interpolated, not extrapolated.
std::vector<double> lattice_point(std::span<const double> z, double h);

// Where a diagnosis runs what it runs "at the fit" z (the budget, the next test): with the local
// design the fit's lattice node (the coordinates beyond the strengths kept), with the global grids
// the fit itself.
std::vector<double> study_point(const DiagnosisCampaign& c, const std::vector<double>& z);

// The lattice node nearest z and its four arms +- h along each strength axis.
std::vector<std::vector<double>> star(std::span<const double> z, double h);

// Batches, each in parallel on the pool: the base grid; the star at the base fit on it; while the
// fit on grid and stars lies at another node (at most kStarMoves times), the star there.
Samples run_local_base(const DiagnosisCampaign& c, Evaluator& evaluator);
// Every effect's points, first around the base fit on grid and star (samples[0], the base's) moved
// by the effect's fit_shift (one per campaign candidate, or none when not screened): an effect
// continuous at neutral runs each level s at the node of the base fit + s x its shift (the path its
// fit takes as the effect grows), its arms at s = 1; one that jumps at neutral runs its stars at
// the node of the full shift. Then, while an effect's fit on its runs lies at a node it has no runs
// at (at most kEffectMoves times), its design there. A batch per step, every effect's in it. As
// run_effect_grids, the result has one more Samples per campaign candidate.
void run_local_effects(const DiagnosisCampaign& c, Evaluator& evaluator,
                       std::vector<Samples>& samples,
                       const std::vector<std::array<double, 2>>& fit_shifts);

}  // namespace rockcal::diagnosis
