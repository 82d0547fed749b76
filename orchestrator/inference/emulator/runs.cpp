#include "orchestrator/inference/emulator/runs.hpp"

#include <numeric>

namespace rockcal::inference {

GpData gp_data(const std::vector<PointRuns>& points) {
  int n = 0;
  for (const PointRuns& p : points) n += p.values.empty() ? 0 : 1;
  const int dims = points.empty() ? 0 : int(points.front().x.size());
  GpData d{Eigen::MatrixXd(n, dims), Eigen::VectorXd(n), Eigen::VectorXd::Zero(n),
           Eigen::VectorXd(n)};
  int row = 0;
  for (const PointRuns& p : points) {
    if (p.values.empty()) continue;
    d.x.row(row) = p.x.transpose();
    d.y(row) = std::accumulate(p.values.begin(), p.values.end(), 0.0) / double(p.values.size());
    d.runs(row) = double(p.values.size());
    ++row;
  }
  return d;
}

double per_run_noise(const Gp& gp) {
  return gp.hyper.nugget;
}

}  // namespace rockcal::inference
