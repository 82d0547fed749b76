// Response surfaces and their calibration: exact on a quadratic, refused where they cannot be
// fitted, and the surface calibration finds a known minimum.
#include <gtest/gtest.h>

#include <cmath>

#include "orchestrator/diagnosis/grid.hpp"
#include "orchestrator/diagnosis/surface_fit.hpp"

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
