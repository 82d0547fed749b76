#include "orchestrator/inference/emulator/runs.hpp"

#include <numeric>

namespace rockcal::inference {

GpData gp_data(const std::vector<PointRuns>& points) {
  int n = 0;
  for (const PointRuns& p : points) n += p.values.empty() ? 0 : 1;
  const int dims = points.empty() ? 0 : int(points.front().x.size());
  GpData d{Eigen::MatrixXd(n, dims), Eigen::VectorXd(n), Eigen::VectorXd::Zero(n),
           Eigen::VectorXd(n), Eigen::VectorXd::Zero(n)};
  int row = 0;
  for (const PointRuns& p : points) {
    if (p.values.empty()) continue;
    d.x.row(row) = p.x.transpose();
    const double mean =
        std::accumulate(p.values.begin(), p.values.end(), 0.0) / double(p.values.size());
    d.y(row) = mean;
    d.runs(row) = double(p.values.size());
    for (double v : p.values) d.within_ss(row) += (v - mean) * (v - mean);
    ++row;
  }
  return d;
}

}  // namespace rockcal::inference
