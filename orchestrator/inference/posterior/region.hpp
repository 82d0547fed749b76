// What a posterior says in numbers: its highest-density credible region, the marginal intervals,
// the point of highest density, and whether the region is pinned inside the box.
//
// Why: "unique" is not yes/no. A region that reaches the box's edge is not bounded by the data
// (the edge bounds it), one that is wide says the targets allow a range of parameters; both are
// answers, and each parameter's interval is what a user carries to the next model.
#pragma once

#include <vector>

#include "orchestrator/inference/posterior/posterior.hpp"

namespace rockcal::inference {

struct Region {
  double level = 0.9;
  std::vector<int> cells;       // the highest-density cells holding `level` of the mass
  Eigen::VectorXd lo, hi;       // per dimension: the region's extent (cell edges), in [0, 1]
  Eigen::VectorXd marginal_lo;  // per dimension: the equal-tailed `level` marginal interval
  Eigen::VectorXd marginal_hi;
  // Per dimension: the region reaches the box's lower (upper) edge (a zoomed grid's edge inside
  // the box is not one).
  std::vector<bool> at_lower;
  std::vector<bool> at_upper;
  double mass_fraction_of_box = 0.0;  // the region's share of the box's volume
  bool bounded() const;               // reaches no edge
};

Region credible_region(const PosteriorGrid& grid, double level = 0.9);

// The same posterior on a grid of as many cells over where `grid`'s mass lies: the densest cells
// holding `mass` of it, one cell more on every side.
//
// Why: a posterior narrower than a cell of the whole box (a UCS known to 2% pins a ridge about 0.03
// wide in ln strength, against cells 0.06 wide over a box of a factor 100) is judged at cell
// centres up to half a cell off its ridge, so a truth on the ridge fell in a cell outside the
// region (the formula twins with the UCS known to 2%: 3 of 24 so, though the density at the truth
// itself was inside). Over the mass the cells are as fine as the posterior. Feasibility, when
// the caller has it, must be applied to the new grid again.
PosteriorGrid zoomed_grid(const PosteriorGrid& grid, const std::vector<const Gp*>& emulators,
                          const std::vector<Target>& targets, double mass = 0.9999);

// The `count` cells of highest posterior weight, densest first (all cells when count exceeds them).
std::vector<int> densest_cells(const PosteriorGrid& grid, int count);

// The point of highest posterior density: the densest cell, refined by a bounded local search on
// the continuous density within one cell of it.
Eigen::VectorXd density_peak(const PosteriorGrid& grid, const std::vector<const Gp*>& emulators,
                             const std::vector<Target>& targets);

// Whether x lies in one of the region's cells.
bool in_region(const PosteriorGrid& grid, const Region& region, const Eigen::VectorXd& x);

}  // namespace rockcal::inference
