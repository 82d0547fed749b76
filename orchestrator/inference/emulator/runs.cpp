#include "orchestrator/inference/emulator/runs.hpp"

#include <numeric>

namespace rockcal::inference {
namespace {

double mean_of(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}

double sum_sq_dev(const std::vector<double>& v) {
  const double m = mean_of(v);
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return s;
}

}  // namespace

PooledScatter pooled_scatter(const std::vector<PointRuns>& points) {
  double ss = 0.0;
  int dof = 0;
  for (const PointRuns& p : points) {
    if (p.values.size() < 2) continue;
    ss += sum_sq_dev(p.values);
    dof += int(p.values.size()) - 1;
  }
  return {dof > 0 ? ss / dof : 0.0, dof};
}

GpData gp_data(const std::vector<PointRuns>& points, const PooledScatter& scatter,
               double prior_dof) {
  int n = 0;
  for (const PointRuns& p : points) n += p.values.empty() ? 0 : 1;
  const int dims = points.empty() ? 0 : int(points.front().x.size());
  GpData d{Eigen::MatrixXd(n, dims), Eigen::VectorXd(n), Eigen::VectorXd(n)};
  int row = 0;
  for (const PointRuns& p : points) {
    if (p.values.empty()) continue;
    const int m = int(p.values.size());
    double var = 0.0;
    if (scatter.dof > 0) {
      var = (prior_dof * scatter.per_run_var + sum_sq_dev(p.values)) / (prior_dof + m - 1);
    }
    d.x.row(row) = p.x.transpose();
    d.y(row) = mean_of(p.values);
    d.noise_var(row) = var / m;
    ++row;
  }
  return d;
}

double per_run_noise(const PooledScatter& scatter, const Gp& gp) {
  return scatter.dof > 0 ? scatter.per_run_var : gp.hyper.nugget;
}

}  // namespace rockcal::inference
