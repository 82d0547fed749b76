#include "orchestrator/diagnosis/analysis/surface.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace rockcal::diagnosis {
namespace {

// A span below this (in unit-cube coordinates) is no span: the runs sit on one value of the axis.
constexpr double kMinSpan = 1e-9;
// The most coordinates a surface takes (a candidate has 3), so evaluate needs no allocation.
constexpr int kMaxDims = 8;

Eigen::VectorXd to_box(const Surface& s, std::span<const double> z) {
  Eigen::VectorXd x(s.dims);
  for (int d = 0; d < s.dims; ++d) x(d) = (z[d] - s.lo(d)) / s.span(d);
  return x;
}

// Each run predicted by the emulator conditioned on the others at the fitted hyperparameters;
// NaN when a reduced covariance cannot be factorised.
double leave_one_out_rms(const inference::Gp& gp) {
  const inference::GpData& d = gp.data;
  const Eigen::Index n = d.x.rows();
  double sum = 0.0;
  for (Eigen::Index k = 0; k < n; ++k) {
    inference::GpData rest;
    rest.x.resize(n - 1, d.x.cols());
    rest.y.resize(n - 1);
    rest.noise_var = Eigen::VectorXd::Zero(n - 1);
    for (Eigen::Index i = 0, j = 0; i < n; ++i) {
      if (i == k) continue;
      rest.x.row(j) = d.x.row(i);
      rest.y(j++) = d.y(i);
    }
    try {
      const inference::Gp without = inference::condition_gp(std::move(rest), gp.hyper);
      sum += std::pow(d.y(k) - inference::predict(without, d.x.row(k).transpose()).mean, 2);
    } catch (const std::exception&) {
      return std::numeric_limits<double>::quiet_NaN();
    }
  }
  return std::sqrt(sum / double(n));
}

}  // namespace

int minimum_surface_points(int dims) {
  return 2 * (dims + 1);
}

std::optional<Surface> fit_surface(const std::vector<std::vector<double>>& z,
                                   const std::vector<double>& y) {
  if (z.empty() || z.size() != y.size()) return std::nullopt;
  const int dims = int(z[0].size());
  const int n = int(z.size());
  if (dims == 0 || dims > kMaxDims || n < minimum_surface_points(dims)) return std::nullopt;
  Surface s;
  s.dims = dims;
  s.points = n;
  s.lo = Eigen::VectorXd::Constant(dims, std::numeric_limits<double>::infinity());
  Eigen::VectorXd hi = Eigen::VectorXd::Constant(dims, -std::numeric_limits<double>::infinity());
  for (const auto& p : z) {
    if (int(p.size()) != dims) return std::nullopt;
    for (int d = 0; d < dims; ++d) {
      s.lo(d) = std::min(s.lo(d), p[d]);
      hi(d) = std::max(hi(d), p[d]);
    }
  }
  s.span = hi - s.lo;
  if (!(s.span.minCoeff() > kMinSpan)) return std::nullopt;
  inference::GpData data;
  data.x.resize(n, dims);
  data.y.resize(n);
  data.noise_var = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    data.x.row(i) = to_box(s, z[i]).transpose().cwiseMax(0.0).cwiseMin(1.0);
    data.y(i) = y[i];
  }
  try {
    s.gp = inference::fit_gp(std::move(data));
  } catch (const std::exception&) {
    return std::nullopt;  // no hyperparameters give a positive-definite covariance
  }
  s.rms = leave_one_out_rms(s.gp);
  return s;
}

double evaluate(const Surface& surface, std::span<const double> z) {
  double x[kMaxDims];
  for (int d = 0; d < surface.dims; ++d) x[d] = (z[d] - surface.lo(d)) / surface.span(d);
  return inference::predict_mean(surface.gp, std::span<const double>(x, std::size_t(surface.dims)));
}

double variance_at(const Surface& surface, std::span<const double> z) {
  return inference::predict(surface.gp, to_box(surface, z)).var;
}

}  // namespace rockcal::diagnosis
