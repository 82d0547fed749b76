#include "orchestrator/inference/posterior/posterior.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rockcal::inference {
namespace {

void check(const std::vector<const Gp*>& emulators, const std::vector<Target>& targets) {
  if (emulators.empty() || emulators.size() != targets.size())
    throw std::invalid_argument("posterior: one emulator per target is needed");
  const auto dims = emulators.front()->data.x.cols();
  for (const Gp* gp : emulators) {
    if (gp->data.x.cols() != dims)
      throw std::invalid_argument("posterior: the emulators differ in dimension");
  }
  for (const Target& t : targets) {
    if (!(t.sd > 0) || !(t.discrepancy_sd >= 0) || !std::isfinite(t.value))
      throw std::invalid_argument("posterior: a target needs a finite value and sd > 0");
  }
}

double term(const Target& t, double mean, double var) {
  const double v = t.sd * t.sd + t.discrepancy_sd * t.discrepancy_sd + var;
  const double r = t.value - mean;
  return -0.5 * (r * r / v + std::log(v));
}

}  // namespace

// The log density and normalised weight of every cell from the grid's means and variances.
void reweigh(PosteriorGrid& g, const std::vector<Target>& targets) {
  const auto cells = g.mean.rows();
  g.log_density.resize(cells);
  const bool feasibility = g.log_feasibility.size() == cells;
  for (Eigen::Index c = 0; c < cells; ++c) {
    double l = feasibility ? g.log_feasibility(c) : 0.0;
    for (std::size_t j = 0; j < targets.size(); ++j)
      l += term(targets[j], g.mean(c, Eigen::Index(j)), g.var(c, Eigen::Index(j)));
    g.log_density(c) = l;
  }
  const double top = g.log_density.maxCoeff();
  g.weight = (g.log_density.array() - top).exp();
  g.weight /= g.weight.sum();
}

int default_cells_per_dim(int dims) {
  switch (dims) {
    case 1:
      return 100;
    case 2:
      return 81;
    default:
      return 25;
  }
}

double cell_edge(const PosteriorGrid& grid, int k, double i) {
  return grid.lo(k) + (grid.hi(k) - grid.lo(k)) * i / grid.per_dim;
}

int cell_of(const PosteriorGrid& grid, const Eigen::VectorXd& x) {
  int cell = 0, stride = 1;
  for (int k = 0; k < grid.dims; ++k) {
    const double lo = cell_edge(grid, k, 0), hi = cell_edge(grid, k, grid.per_dim);
    const double f = std::isfinite(x(k)) ? (x(k) - lo) / (hi - lo) : 0.0;
    const int i = int(std::clamp(std::floor(f * grid.per_dim), 0.0, double(grid.per_dim - 1)));
    cell += i * stride;
    stride *= grid.per_dim;
  }
  return cell;
}

std::vector<int> cell_indices(const PosteriorGrid& grid, int cell) {
  std::vector<int> idx(grid.dims);
  for (int k = 0; k < grid.dims; ++k) {
    idx[k] = cell % grid.per_dim;
    cell /= grid.per_dim;
  }
  return idx;
}

PosteriorGrid posterior_on_grid(const std::vector<const Gp*>& emulators,
                                const std::vector<Target>& targets, int per_dim,
                                const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  check(emulators, targets);
  PosteriorGrid g;
  g.dims = int(emulators.front()->data.x.cols());
  if (g.dims > 3) throw std::invalid_argument("posterior: at most 3 parameters on a grid");
  g.per_dim = per_dim > 0 ? per_dim : default_cells_per_dim(g.dims);
  g.lo = lo.size() ? lo : Eigen::VectorXd::Zero(g.dims);
  g.hi = hi.size() ? hi : Eigen::VectorXd::Ones(g.dims);
  if (g.lo.size() != g.dims || g.hi.size() != g.dims || !(g.lo.array() >= 0).all() ||
      !(g.hi.array() <= 1).all() || !(g.lo.array() < g.hi.array()).all())
    throw std::invalid_argument("posterior: the grid's span must lie inside the unit box");
  int cells = 1;
  for (int k = 0; k < g.dims; ++k) cells *= g.per_dim;
  g.points.resize(cells, g.dims);
  for (int c = 0; c < cells; ++c) {
    const std::vector<int> idx = cell_indices(g, c);
    for (int k = 0; k < g.dims; ++k) g.points(c, k) = cell_edge(g, k, idx[k] + 0.5);
  }
  const int n_targets = int(targets.size());
  g.mean.resize(cells, n_targets);
  g.var.resize(cells, n_targets);
  for (int j = 0; j < n_targets; ++j) {
    Eigen::VectorXd m, v;
    predict_many(*emulators[j], g.points, m, v);
    g.mean.col(j) = m;
    g.var.col(j) = v;
  }
  reweigh(g, targets);
  return g;
}

PosteriorGrid with_exact_emulators(const PosteriorGrid& grid, const std::vector<Target>& targets) {
  if (grid.mean.cols() != Eigen::Index(targets.size()))
    throw std::invalid_argument("posterior: one emulator per target is needed");
  PosteriorGrid g = grid;
  g.var.setZero();
  reweigh(g, targets);
  return g;
}

double log_density(const std::vector<const Gp*>& emulators, const std::vector<Target>& targets,
                   const Eigen::VectorXd& x) {
  check(emulators, targets);
  double l = 0.0;
  for (std::size_t j = 0; j < targets.size(); ++j) {
    const Prediction p = predict(*emulators[j], x);
    l += term(targets[j], p.mean, p.var);
  }
  return l;
}

}  // namespace rockcal::inference
