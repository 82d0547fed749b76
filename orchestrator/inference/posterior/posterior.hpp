// The posterior of the parameters given measured targets, through the emulators.
//
// Why: a lab value is known to its own uncertainty, an emulator to its variance, and a model to
// the discrepancy one states for it. A calibration that returns one point hides all three; the
// posterior p(x | targets) ~ prior(x) * prod_j N(t_j; mu_j(x), sd_j^2 + disc_j^2 + var_j(x)) keeps
// them, and its credible region is the answer. The prior is uniform on the box (log-uniform
// strengths when the box is in log strengths). With at most three parameters the posterior is
// evaluated on a grid of cell centres, which needs no sampler and no convergence check.
#pragma once

#include <vector>

#include "orchestrator/inference/emulator/gp.hpp"

namespace rockcal::inference {

// One measured target in the emulator's space (e.g. ln of a peak load), with the standard
// deviation of the measurement and of the model's stated discrepancy in the same space.
struct Target {
  double value = 0.0;
  double sd = 0.05;
  double discrepancy_sd = 0.0;
};

struct PosteriorGrid {
  int dims = 0;
  int per_dim = 0;
  // The part of the unit box the cells span, per dimension: the whole box, or where the mass of
  // a coarser grid lies (zoomed_grid in region.hpp).
  Eigen::VectorXd lo, hi;
  Eigen::MatrixXd points;       // cells x dims: the cell centres
  Eigen::VectorXd log_density;  // unnormalised
  Eigen::VectorXd weight;       // normalised to sum 1
  Eigen::MatrixXd mean;         // cells x targets: the emulators' means
  Eigen::MatrixXd var;          // cells x targets: the emulators' variances
  // Cells: the log chance that a run there gives the targets' observables at all
  // (feasibility.hpp), added to the log density; empty = every cell feasible.
  Eigen::VectorXd log_feasibility;
};

// Cells per dimension that keep the grid near 10^4 cells: 100 in 1-D, 81 in 2-D, 25 in 3-D.
int default_cells_per_dim(int dims);

// Throws std::invalid_argument when emulators and targets differ in number or dimension. `lo`,
// `hi`: the span of the cells in the unit box (empty: the whole box).
PosteriorGrid posterior_on_grid(const std::vector<const Gp*>& emulators,
                                const std::vector<Target>& targets, int per_dim = 0,
                                const Eigen::VectorXd& lo = {}, const Eigen::VectorXd& hi = {});

// Where the grid's cell edge i (0 .. per_dim) of dimension k lies in the unit box.
double cell_edge(const PosteriorGrid& grid, int k, double i);

// The same posterior with every emulator's variance set to zero: what the targets' own uncertainty
// and the stated discrepancy allow if the emulators' means were exact. Its region is the narrowest
// that more runs can reach; a region wider than wanted here needs another test, not more runs.
PosteriorGrid with_exact_emulators(const PosteriorGrid& grid, const std::vector<Target>& targets);

// Recomputes the grid's log density and weights from its means, variances and feasibility.
void reweigh(PosteriorGrid& grid, const std::vector<Target>& targets);

// The log posterior density at any x (the same expression as on the grid).
double log_density(const std::vector<const Gp*>& emulators, const std::vector<Target>& targets,
                   const Eigen::VectorXd& x);

// The cell that holds x (outside the grid's span, the nearest cell).
int cell_of(const PosteriorGrid& grid, const Eigen::VectorXd& x);

// The index of cell (i_1, ..., i_d) and back.
std::vector<int> cell_indices(const PosteriorGrid& grid, int cell);

}  // namespace rockcal::inference
