#include "orchestrator/diagnosis/analysis/fit_spread.hpp"

#include <algorithm>
#include <cmath>

#include "orchestrator/diagnosis/analysis/gap.hpp"

namespace rockcal::diagnosis {

std::vector<double> fit_spread(const SurfaceSet& surfaces, const std::vector<double>& z,
                               const std::vector<Target>& targets,
                               const std::vector<double>& budget) {
  std::vector<double> out(targets.size(), 0.0);
  if (z.empty() || surfaces.per_target.size() != targets.size()) return out;
  const std::vector<std::vector<double>> grad = surface_gradients(surfaces, z);
  const int dims = int(z.size());
  Eigen::MatrixXd g(grad.size(), dims);
  for (std::size_t i = 0; i < grad.size(); ++i)
    for (int d = 0; d < dims; ++d) g(i, d) = grad[i][d];
  constexpr double kBoxPrecision = 12.0;  // 1 / the variance of a uniform unit interval
  Eigen::MatrixXd precision = kBoxPrecision * Eigen::MatrixXd::Identity(dims, dims);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (targets[i].role != Role::calibration || !g.row(i).allFinite()) continue;
    const double scale = std::max(noise_scale(targets[i], budget[i]), kMinNoiseScale);
    precision += g.row(i).transpose() * g.row(i) / (scale * scale);
  }
  const Eigen::MatrixXd sigma = precision.ldlt().solve(Eigen::MatrixXd::Identity(dims, dims));
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (g.row(i).allFinite()) out[i] = std::max(0.0, (g.row(i) * sigma * g.row(i).transpose())(0));
  }
  return out;
}

}  // namespace rockcal::diagnosis
