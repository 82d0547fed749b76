// Response surfaces and their calibration: exact on a quadratic, refused where they cannot be
// fitted, and the surface calibration finds a known minimum.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "orchestrator/diagnosis/analysis/surface_fit.hpp"
#include "orchestrator/diagnosis/pipeline/grid.hpp"

namespace rockcal::diagnosis {
namespace {

double quadratic(const std::vector<double>& z) {
  const double x = z[0], y = z[1], s = z.size() > 2 ? z[2] : 0.0;
  return 1.5 - 0.7 * x + 0.3 * y + 2.0 * x * x - 0.4 * x * y + 0.9 * y * y + 0.8 * s - 1.1 * s * s +
         0.25 * x * s - 0.6 * y * s;
}

std::vector<std::vector<double>> grid(int dims) {
  std::vector<std::vector<double>> z;
  for (double x : grid_axis(4)) {
    for (double y : grid_axis(4)) {
      if (dims == 2) {
        z.push_back({x, y});
        continue;
      }
      for (double s : grid_axis(3)) z.push_back({x, y, s});
    }
  }
  return z;
}

TEST(Surface, ExactOnAQuadraticIn2DAnd3D) {
  for (int dims : {2, 3}) {
    const auto z = grid(dims);
    std::vector<double> y;
    for (const auto& p : z) y.push_back(quadratic(p));
    const auto fit = fit_surface(z, y);
    ASSERT_TRUE(fit) << dims;
    EXPECT_LT(fit->rms, 1e-12);
    EXPECT_EQ(fit->points, int(z.size()));
    // Exact between the grid nodes too, where nothing was fitted.
    for (const std::vector<double>& p :
         std::vector<std::vector<double>>{{0.1, 0.77, 0.3}, {0.5, 0.5, 0.9}, {0.93, 0.02, 0.61}}) {
      std::vector<double> q(p.begin(), p.begin() + dims);
      EXPECT_NEAR(evaluate(*fit, q), quadratic(q), 1e-10);
    }
  }
}

// A smooth response that a quadratic cannot follow: a saturating strength dependence, as a peak
// load limited by the weaker of two bond strengths.
double saturating(const std::vector<double>& z) {
  return -0.5 * std::log(std::exp(-6.0 * z[0]) + std::exp(-6.0 * z[1] - 0.6));  // a smooth min
}

double max_error_between_nodes(const Surface& fit, double (*f)(const std::vector<double>&)) {
  double worst = 0.0;
  for (double x = 0.05; x < 1.0; x += 0.1)
    for (double y = 0.05; y < 1.0; y += 0.1) {
      const std::vector<double> q{x, y};
      worst = std::max(worst, std::abs(evaluate(fit, q) - f(q)));
    }
  return worst;
}

TEST(Surface, FollowsAResponseThatIsNotQuadratic) {
  const auto z = grid(2);
  std::vector<double> y;
  for (const auto& p : z) y.push_back(saturating(p));
  const auto fit = fit_surface(z, y);
  ASSERT_TRUE(fit);
  // The least-squares quadratic, the limit of large smoothing, for comparison.
  const auto quad = fit_surface(z, y, 1e6);
  ASSERT_TRUE(quad);
  const double err = max_error_between_nodes(*fit, saturating);
  const double err_quad = max_error_between_nodes(*quad, saturating);
  EXPECT_LT(err, 0.5 * err_quad) << err << " vs " << err_quad;
  EXPECT_EQ(fit->smoothing, 0.0);  // smooth data: interpolation wins the cross-validation
  for (std::size_t k = 0; k < z.size(); ++k) EXPECT_NEAR(evaluate(*fit, z[k]), y[k], 1e-9);
}

TEST(Surface, LeaveOneOutRmsIsWhatRefittingWithoutEachPointGives) {
  const auto z = grid(3);
  std::vector<double> y;
  for (const auto& p : z) y.push_back(saturating(p) + 0.5 * p[2] * p[0]);
  for (double smoothing : {0.0, 0.01}) {
    const auto fit = fit_surface(z, y, smoothing);
    ASSERT_TRUE(fit);
    double sum = 0.0;
    for (std::size_t k = 0; k < z.size(); ++k) {
      auto zk = z;
      auto yk = y;
      zk.erase(zk.begin() + k);
      yk.erase(yk.begin() + k);
      const auto without = fit_surface(zk, yk, smoothing);
      ASSERT_TRUE(without);
      const double e = y[k] - evaluate(*without, z[k]);
      sum += e * e;
    }
    EXPECT_NEAR(fit->rms, std::sqrt(sum / z.size()), 1e-8) << smoothing;
  }
}

TEST(Surface, ScatteredRunsAreSmoothedNotInterpolated) {
  // A quadratic plus run-to-run scatter of up to 0.05 (mt19937's raw draws: the same everywhere):
  // the cross-validated surface averages it, and lands closer to the quadratic than the runs are.
  const auto z = grid(3);
  std::vector<double> y;
  double scatter = 0.0;
  std::mt19937 rng(4);
  for (std::size_t k = 0; k < z.size(); ++k) {
    const double noise = 0.1 * (double(rng()) / 4294967296.0 - 0.5);
    scatter += noise * noise;
    y.push_back(quadratic(z[k]) + noise);
  }
  scatter = std::sqrt(scatter / z.size());
  const auto fit = fit_surface(z, y);
  ASSERT_TRUE(fit);
  EXPECT_GT(fit->smoothing, 0.0);
  double off = 0.0;
  for (const auto& p : z) off += std::pow(evaluate(*fit, p) - quadratic(p), 2);
  EXPECT_LT(std::sqrt(off / z.size()), 0.8 * scatter);
}

TEST(Surface, RefusedWithTooFewOrDegeneratePoints) {
  EXPECT_FALSE(fit_surface({{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0.5, 0.5}}, {1, 2, 3, 4, 5}));
  // Six points on one line cannot pin a quadratic in two variables.
  std::vector<std::vector<double>> line;
  std::vector<double> y;
  for (int k = 0; k < 6; ++k) {
    line.push_back({0.2 * k, 0.5});
    y.push_back(k);
  }
  EXPECT_FALSE(fit_surface(line, y));
}

TEST(Surface, CalibrationFindsTheMinimumAndKeepsAHistory) {
  // Three observables, each monotone in one coordinate: the point that reproduces them is unique.
  const std::vector<double> truth{0.3, 0.65, 0.4};
  SurfaceSet set{3, {}};
  const auto z = grid(3);
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> y;
    for (const auto& p : z)
      y.push_back(p[axis] + 0.2 * p[axis] * p[(axis + 1) % 3] - 0.1 * p[axis] * p[axis]);
    set.per_target.push_back(fit_surface(z, y));
  }
  Objective objective{predict(set, truth), {1.0, 1.0, 1.0}};
  const SurfaceCalibration fit = calibrate_on_surfaces(set, objective, lattice_starts(3, 2));
  EXPECT_LT(fit.misfit, 1e-12);
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(fit.z[d], truth[d], 1e-4);
  ASSERT_FALSE(fit.history.empty());
  EXPECT_DOUBLE_EQ(fit.history.back(), fit.misfit);
  for (std::size_t k = 1; k < fit.history.size(); ++k)
    EXPECT_LE(fit.history[k], fit.history[k - 1]);
  // With s held fixed the search moves the strengths only.
  const SurfaceCalibration held = calibrate_on_surfaces(set, objective, lattice_starts(3, 2), 0.9);
  EXPECT_DOUBLE_EQ(held.z[2], 0.9);
  EXPECT_GT(held.misfit, 1e-6);
}

}  // namespace
}  // namespace rockcal::diagnosis
