#include "orchestrator/inference/posterior/feasibility.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace rockcal::inference {

Eigen::VectorXd squared_distances(const Eigen::MatrixXd& at, const Eigen::VectorXd& x,
                                  const FeasibilitySettings& s) {
  const Eigen::MatrixXd d = at.rowwise() - x.transpose();
  if (s.metric.size() == 0) return d.rowwise().squaredNorm();
  return (d * s.metric).cwiseProduct(d).rowwise().sum();
}

double feasibility(const RunResults& runs, const Eigen::VectorXd& x, const FeasibilitySettings& s) {
  if (runs.x.rows() != runs.has_value.size())
    throw std::invalid_argument("feasibility: one outcome per run is needed");
  if (runs.x.rows() == 0) return 1.0;
  const Eigen::VectorXd d2 = squared_distances(runs.x, x, s);
  const double nearest = d2.minCoeff();
  double sum_w = 0.0, sum_wy = 0.0;
  for (Eigen::Index i = 0; i < runs.x.rows(); ++i) {
    const double w = std::exp(-0.5 * (d2(i) - nearest) / (s.length * s.length));
    sum_w += w;
    sum_wy += w * runs.has_value(i);
  }
  return (sum_wy + s.prior_weight) / (sum_w + s.prior_weight);
}

RunResults overlaid(const RunResults& under, const RunResults& over, double reach,
                    const FeasibilitySettings& s) {
  std::vector<Eigen::Index> kept;
  for (Eigen::Index i = 0; i < under.x.rows(); ++i) {
    const bool covered =
        over.x.rows() > 0 &&
        squared_distances(over.x, under.x.row(i).transpose(), s).minCoeff() <= reach * reach;
    if (!covered) kept.push_back(i);
  }
  RunResults r;
  r.x.resize(Eigen::Index(kept.size()) + over.x.rows(),
             under.x.cols() ? under.x.cols() : over.x.cols());
  r.has_value.resize(r.x.rows());
  Eigen::Index k = 0;
  for (Eigen::Index i : kept) {
    r.x.row(k) = under.x.row(i);
    r.has_value(k++) = under.has_value(i);
  }
  for (Eigen::Index i = 0; i < over.x.rows(); ++i) {
    r.x.row(k) = over.x.row(i);
    r.has_value(k++) = over.has_value(i);
  }
  return r;
}

void apply_feasibility(PosteriorGrid& grid, const RunResults& runs,
                       const std::vector<Target>& targets, const FeasibilitySettings& s) {
  if (runs.x.rows() == 0) {
    grid.log_feasibility.resize(0);
  } else {
    grid.log_feasibility.resize(grid.points.rows());
    for (Eigen::Index c = 0; c < grid.points.rows(); ++c)
      grid.log_feasibility(c) = std::log(feasibility(runs, grid.points.row(c).transpose(), s));
  }
  reweigh(grid, targets);
}

}  // namespace rockcal::inference
