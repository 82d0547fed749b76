// Focus: the response surfaces (the inference core's emulator over the design's runs) and their
// calibration: they follow a smooth response between the runs, on a global grid and on a local
// star, take scatter as noise, say by their variance where the runs pin them, are refused where
// they cannot be fitted, and the surface calibration finds a known minimum.
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

TEST(Surface, ReproducesASmoothResponseBetweenTheRuns) {
  for (int dims : {2, 3}) {
    const auto z = grid(dims);
    std::vector<double> y;
    for (const auto& p : z) y.push_back(quadratic(p));
    const auto fit = fit_surface(z, y);
    ASSERT_TRUE(fit) << dims;
    EXPECT_LT(fit->rms, 0.02) << dims;
    EXPECT_EQ(fit->points, int(z.size()));
    // Between the grid nodes too, where nothing was fitted: within 0.02 in ln (the response spans
    // about 3; a plane through the runs misses it by 0.3).
    for (const std::vector<double>& p :
         std::vector<std::vector<double>>{{0.1, 0.77, 0.3}, {0.5, 0.5, 0.9}, {0.93, 0.02, 0.61}}) {
      std::vector<double> q(p.begin(), p.begin() + dims);
      EXPECT_NEAR(evaluate(*fit, q), quadratic(q), 0.02) << dims;
    }
  }
}

// A smooth response that a quadratic cannot follow: a saturating strength dependence, as a peak
// load limited by the weaker of two bond strengths.
double saturating(const std::vector<double>& z) {
  return -0.5 * std::log(std::exp(-6.0 * z[0]) + std::exp(-6.0 * z[1] - 0.6));  // a smooth min
}

double max_error_between_nodes(const Surface& fit, double (*f)(const std::vector<double>&),
                               double lo = 0.0, double width = 1.0) {
  double worst = 0.0;
  for (double x = 0.05; x < 1.0; x += 0.1)
    for (double y = 0.05; y < 1.0; y += 0.1) {
      const std::vector<double> q{lo + width * x, lo + width * y};
      worst = std::max(worst, std::abs(evaluate(fit, q) - f(q)));
    }
  return worst;
}

TEST(Surface, FollowsAResponseThatIsNotQuadratic) {
  const auto z = grid(2);
  std::vector<double> y;
  double range = 0.0;
  for (const auto& p : z) y.push_back(saturating(p));
  for (double v : y) range = std::max(range, std::abs(v - y[0]));
  const auto fit = fit_surface(z, y);
  ASSERT_TRUE(fit);
  // Within 5% of the response's range anywhere between the 4 x 4 runs.
  EXPECT_LT(max_error_between_nodes(*fit, saturating), 0.05 * range);
  for (std::size_t k = 0; k < z.size(); ++k) EXPECT_NEAR(evaluate(*fit, z[k]), y[k], 0.005);
}

TEST(Surface, ALocalStarIsResolvedAsAGlobalGridIs) {
  // The same response over a star a tenth of the box wide (a local design's runs): the emulator
  // works in the runs' own box, so it follows the response there as closely, relative to what
  // the response does across the star.
  std::vector<std::vector<double>> z;
  std::vector<double> y;
  double range = 0.0;
  for (const auto& p : grid(2)) {
    z.push_back({0.45 + 0.1 * p[0], 0.45 + 0.1 * p[1]});
    y.push_back(10.0 * saturating({10.0 * z.back()[0] - 4.5, 10.0 * z.back()[1] - 4.5}));
  }
  for (double v : y) range = std::max(range, std::abs(v - y[0]));
  const auto fit = fit_surface(z, y);
  ASSERT_TRUE(fit);
  auto local = [](const std::vector<double>& q) {
    return 10.0 * saturating({10.0 * q[0] - 4.5, 10.0 * q[1] - 4.5});
  };
  double worst = 0.0;
  for (double a = 0.05; a < 1.0; a += 0.1)
    for (double b = 0.05; b < 1.0; b += 0.1) {
      const std::vector<double> q{0.45 + 0.1 * a, 0.45 + 0.1 * b};
      worst = std::max(worst, std::abs(evaluate(*fit, q) - local(q)));
    }
  EXPECT_LT(worst, 0.05 * range);
}

TEST(Surface, ScatteredRunsAreSmoothedNotInterpolated) {
  // A quadratic plus run-to-run scatter of up to 0.05 (mt19937's raw draws: the same everywhere):
  // the emulator takes it as noise (a nugget), lands closer to the quadratic than the runs are,
  // and its leave-one-out rms is about the scatter.
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
  EXPECT_GT(fit->gp.hyper.nugget, 0.1 * scatter * scatter);
  double off = 0.0;
  for (const auto& p : z) off += std::pow(evaluate(*fit, p) - quadratic(p), 2);
  EXPECT_LT(std::sqrt(off / z.size()), 0.8 * scatter);
  EXPECT_GT(fit->rms, 0.7 * scatter);
  EXPECT_LT(fit->rms, 1.6 * scatter);
}

TEST(Surface, ItsVarianceSaysWhereTheRunsPinIt) {
  // Scattered runs on the left half of the box only: at a run the emulator's variance is below
  // one run's scatter (it pools the neighbours); far beyond the runs it is many times that.
  std::vector<std::vector<double>> z;
  std::vector<double> y;
  std::mt19937 rng(7);
  for (const auto& p : grid(2)) {
    z.push_back({0.5 * p[0], p[1]});
    y.push_back(quadratic(z.back()) + 0.1 * (double(rng()) / 4294967296.0 - 0.5));
  }
  const auto fit = fit_surface(z, y);
  ASSERT_TRUE(fit);
  const double at_run = variance_at(*fit, z[5]);
  const double beyond = variance_at(*fit, std::vector<double>{1.0, 0.5});
  const double one_run = fit->gp.hyper.nugget;
  EXPECT_LT(at_run, one_run);
  EXPECT_GT(beyond, 4.0 * one_run);
}

TEST(Surface, RefusedWithTooFewOrDegeneratePoints) {
  EXPECT_FALSE(fit_surface({{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0.5, 0.5}}, {1, 2, 3, 4, 5}));
  // Six points on one line say nothing of the other axis.
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
