#include "orchestrator/inference/posterior/region.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <nlopt.hpp>

namespace rockcal::inference {
namespace {

// The equal-tailed interval of one dimension's marginal.
std::pair<double, double> marginal(const PosteriorGrid& grid, int dim, double level) {
  std::vector<double> mass(grid.per_dim, 0.0);
  for (int c = 0; c < grid.weight.size(); ++c) mass[cell_indices(grid, c)[dim]] += grid.weight(c);
  const double tail = 0.5 * (1.0 - level);
  auto edge = [&](double q) {
    double cum = 0.0;
    for (int i = 0; i < grid.per_dim; ++i) {
      if (cum + mass[i] >= q) {  // linear within the cell
        const double f = mass[i] > 0 ? (q - cum) / mass[i] : 0.0;
        return cell_edge(grid, dim, i + f);
      }
      cum += mass[i];
    }
    return cell_edge(grid, dim, grid.per_dim);
  };
  return {edge(tail), edge(1.0 - tail)};
}

struct PeakSearch {
  const std::vector<const Gp*>* emulators;
  const std::vector<Target>* targets;
};

double negative_log_density(unsigned n, const double* x, double*, void* data) {
  auto* s = static_cast<PeakSearch*>(data);
  return -log_density(*s->emulators, *s->targets, Eigen::Map<const Eigen::VectorXd>(x, n));
}

}  // namespace

bool Region::bounded() const {
  return std::none_of(at_lower.begin(), at_lower.end(), [](bool b) { return b; }) &&
         std::none_of(at_upper.begin(), at_upper.end(), [](bool b) { return b; });
}

Region credible_region(const PosteriorGrid& grid, double level) {
  Region r;
  r.level = level;
  std::vector<int> order(grid.weight.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return grid.weight(a) > grid.weight(b); });
  double mass = 0.0;
  for (int c : order) {
    r.cells.push_back(c);
    mass += grid.weight(c);
    if (mass >= level) break;
  }
  r.lo = Eigen::VectorXd::Constant(grid.dims, 1.0);
  r.hi = Eigen::VectorXd::Zero(grid.dims);
  r.at_lower.assign(grid.dims, false);
  r.at_upper.assign(grid.dims, false);
  for (int c : r.cells) {
    const std::vector<int> idx = cell_indices(grid, c);
    for (int k = 0; k < grid.dims; ++k) {
      r.lo(k) = std::min(r.lo(k), cell_edge(grid, k, idx[k]));
      r.hi(k) = std::max(r.hi(k), cell_edge(grid, k, idx[k] + 1));
      if (idx[k] == 0 && cell_edge(grid, k, 0) <= 0.0) r.at_lower[k] = true;
      if (idx[k] == grid.per_dim - 1 && cell_edge(grid, k, grid.per_dim) >= 1.0)
        r.at_upper[k] = true;
    }
  }
  r.marginal_lo.resize(grid.dims);
  r.marginal_hi.resize(grid.dims);
  for (int k = 0; k < grid.dims; ++k) {
    const auto [lo, hi] = marginal(grid, k, level);
    r.marginal_lo(k) = lo;
    r.marginal_hi(k) = hi;
  }
  double span = 1.0;
  for (int k = 0; k < grid.dims; ++k)
    span *= cell_edge(grid, k, grid.per_dim) - cell_edge(grid, k, 0);
  r.mass_fraction_of_box = span * double(r.cells.size()) / double(grid.weight.size());
  return r;
}

PosteriorGrid zoomed_grid(const PosteriorGrid& grid, const std::vector<const Gp*>& emulators,
                          const std::vector<Target>& targets, double mass) {
  Eigen::VectorXd lo = Eigen::VectorXd::Constant(grid.dims, 1.0);
  Eigen::VectorXd hi = Eigen::VectorXd::Zero(grid.dims);
  for (int c : credible_region(grid, mass).cells) {
    const std::vector<int> idx = cell_indices(grid, c);
    for (int k = 0; k < grid.dims; ++k) {
      lo(k) = std::min(lo(k), cell_edge(grid, k, idx[k] - 1));
      hi(k) = std::max(hi(k), cell_edge(grid, k, idx[k] + 2));
    }
  }
  for (int k = 0; k < grid.dims; ++k) {
    lo(k) = std::max(lo(k), cell_edge(grid, k, 0));
    hi(k) = std::min(hi(k), cell_edge(grid, k, grid.per_dim));
  }
  return posterior_on_grid(emulators, targets, grid.per_dim, lo, hi);
}

Eigen::VectorXd density_peak(const PosteriorGrid& grid, const std::vector<const Gp*>& emulators,
                             const std::vector<Target>& targets) {
  Eigen::Index best = 0;
  grid.log_density.maxCoeff(&best);
  std::vector<double> x(grid.dims), lo(grid.dims), hi(grid.dims);
  for (int k = 0; k < grid.dims; ++k) {
    x[k] = grid.points(best, k);
    const double width = cell_edge(grid, k, 1) - cell_edge(grid, k, 0);
    lo[k] = std::max(0.0, x[k] - width);
    hi[k] = std::min(1.0, x[k] + width);
  }
  PeakSearch search{&emulators, &targets};
  nlopt::opt opt(grid.dims == 1 ? nlopt::LN_COBYLA : nlopt::LN_BOBYQA, unsigned(grid.dims));
  opt.set_lower_bounds(lo);
  opt.set_upper_bounds(hi);
  opt.set_min_objective(negative_log_density, &search);
  opt.set_xtol_abs(1e-5);
  opt.set_maxeval(200);
  double value = 0.0;
  try {
    opt.optimize(x, value);
  } catch (const std::exception&) {
    // The densest cell's centre stands.
    for (int k = 0; k < grid.dims; ++k) x[k] = grid.points(best, k);
  }
  return Eigen::Map<Eigen::VectorXd>(x.data(), grid.dims);
}

bool in_region(const PosteriorGrid& grid, const Region& region, const Eigen::VectorXd& x) {
  const int cell = cell_of(grid, x);
  return std::find(region.cells.begin(), region.cells.end(), cell) != region.cells.end();
}

std::vector<int> densest_cells(const PosteriorGrid& grid, int count) {
  std::vector<int> order(grid.weight.size());
  std::iota(order.begin(), order.end(), 0);
  const int m = std::clamp(count, 0, int(order.size()));
  std::partial_sort(order.begin(), order.begin() + m, order.end(),
                    [&](int a, int b) { return grid.weight(a) > grid.weight(b); });
  order.resize(m);
  return order;
}

}  // namespace rockcal::inference
