// Focus: the emulator. Its mean recovers a smooth function from noisy runs, its variance is
// honest (the truth lies inside its 90% band about 90% of the time), a point's own noise keeps it
// from being interpolated, and bad data are refused with exact errors.
#include <gtest/gtest.h>

#include <random>

#include "orchestrator/inference/emulator/gp.hpp"
#include "orchestrator/inference/emulator/runs.hpp"
#include "orchestrator/inference/emulator/two_level.hpp"
#include "test_functions.hpp"

namespace rockcal::inference {
namespace {

using testing::latin_square;
using testing::ln_uct;

GpData noisy(int n, double sd, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sd);
  GpData d{
      latin_square(n, seed), Eigen::VectorXd(n), Eigen::VectorXd::Constant(n, sd * sd), {}, {}};
  for (int i = 0; i < n; ++i) d.y(i) = ln_uct(d.x.row(i).transpose()) + noise(rng);
  return d;
}

TEST(Emulator, ItsMeanRecoversASmoothFunctionAndItsBandCoversTheTruth) {
  int inside = 0, total = 0;
  double sq = 0.0;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Gp gp = fit_gp(noisy(30, 0.05, seed));
    const Eigen::MatrixXd test = latin_square(100, 100 + seed);
    for (int i = 0; i < test.rows(); ++i) {
      const Eigen::VectorXd x = test.row(i).transpose();
      const Prediction p = predict(gp, x);
      const double e = p.mean - ln_uct(x);
      sq += e * e;
      inside += std::abs(e) <= 1.645 * std::sqrt(p.var) ? 1 : 0;
      ++total;
    }
  }
  EXPECT_LT(std::sqrt(sq / total), 0.04);  // below the runs' own noise of 0.05
  // Measured 0.81: a plug-in likelihood fit is a little overconfident (its hyperparameters'
  // own uncertainty is not in the band); the calibration's coverage is proven on twins.
  const double coverage = double(inside) / total;
  EXPECT_GT(coverage, 0.75);
  EXPECT_LT(coverage, 0.99);
}

TEST(Emulator, APointsOwnNoiseKeepsItFromBeingInterpolated) {
  GpData d = noisy(25, 0.01, 7);
  d.y(0) += 1.0;  // an outlier...
  const Eigen::VectorXd x0 = d.x.row(0).transpose();
  const double truth = ln_uct(x0);
  GpData loud = d;
  loud.noise_var(0) = 1.0;  // ...that its own scatter says is one
  const Gp quiet_fit = condition_gp(d, fit_gp(d).hyper);
  const Gp loud_fit = fit_gp(loud);
  EXPECT_LT(std::abs(predict(loud_fit, x0).mean - truth), 0.1);
  EXPECT_GT(std::abs(predict(quiet_fit, x0).mean - truth), 0.3);
}

TEST(Emulator, VarianceShrinksWhereThereAreRuns) {
  const Gp gp = fit_gp(noisy(20, 0.02, 3));
  Eigen::VectorXd near = gp.data.x.row(0).transpose();
  const Eigen::VectorXd far = Eigen::VectorXd::Constant(2, 2.0);  // outside the box: extrapolation
  EXPECT_LT(predict(gp, near).var, predict(gp, far).var);
}

TEST(Emulator, TheMeanAloneIsThePredictionsMeanWithItsBase) {
  // predict_mean is what searches call thousands of times; it must be the same number.
  const Gp coarse = fit_gp(noisy(20, 0.02, 5));
  GpData fine = noisy(8, 0.02, 6);
  fine.y.array() += 0.1;
  const Gp two = fit_two_level(coarse, fine);
  for (const Gp* gp : {&coarse, &two}) {
    for (const Eigen::VectorXd& x : {Eigen::VectorXd(Eigen::Vector2d(0.3, 0.8)),
                                     Eigen::VectorXd(Eigen::Vector2d(1.4, -0.2))}) {
      EXPECT_NEAR(predict_mean(*gp, std::span<const double>(x.data(), 2)), predict(*gp, x).mean,
                  1e-12);
    }
  }
}

TEST(Emulator, OneRunsScatterIsLearnedAndAPointOfManyRunsIsKnownBetter) {
  // 40 points, 1 to 3 runs each, one run's scatter sd 0.2 about a smooth function.
  std::mt19937 rng(17);
  std::normal_distribution<double> noise(0.0, 0.2);
  const Eigen::MatrixXd x = latin_square(40, 17);
  std::vector<PointRuns> points;
  for (int i = 0; i < 40; ++i) {
    PointRuns p{x.row(i).transpose(), {}};
    for (int k = 0; k <= i % 3; ++k) p.values.push_back(ln_uct(p.x) + noise(rng));
    points.push_back(p);
  }
  const GpData d = gp_data(points);
  ASSERT_EQ(d.y.size(), 40);
  EXPECT_EQ(d.runs(2), 3.0);
  EXPECT_NEAR(d.y(1), 0.5 * (points[1].values[0] + points[1].values[1]), 1e-12);
  const Gp gp = fit_gp(d);
  EXPECT_NEAR(std::sqrt(gp.hyper.nugget), 0.2, 0.06);
  // The same point with three runs instead of one: its mean is known better.
  GpData more = d;
  more.runs(0) = 10;
  const Eigen::VectorXd x0 = d.x.row(0).transpose();
  EXPECT_LT(predict(condition_gp(more, gp.hyper), x0).var, predict(gp, x0).var);
}

// One run's scatter 0.02 in ln where x_2 < x_1 (a specimen whose shear bonds are the weaker:
// nearly the same failure on every packing) and 0.12 elsewhere, 120 runs on 60 points. With the
// noise trend the emulator learns both scatters (a log-linear model of the step) and follows the
// quiet runs closely; one scatter for the box smooths them with the loud ones' variance.
TEST(Emulator, ANoiseTrendLearnsAScatterThatChangesAcrossTheBox) {
  std::mt19937 rng(5);
  std::normal_distribution<double> unit(0.0, 1.0);
  const auto sd_at = [](const Eigen::VectorXd& x) { return x(1) < x(0) ? 0.02 : 0.12; };
  const Eigen::MatrixXd x = latin_square(60, 5);
  std::vector<PointRuns> points;
  for (int i = 0; i < 60; ++i) {
    PointRuns p{x.row(i).transpose(), {}};
    for (int k = 0; k < 2; ++k) p.values.push_back(ln_uct(p.x) + sd_at(p.x) * unit(rng));
    points.push_back(p);
  }
  GpOptions o;
  o.noise_trend = true;
  const Gp trend = fit_gp(gp_data(points), o);
  const Gp flat = fit_gp(gp_data(points));
  const Eigen::Vector2d quiet(0.85, 0.15), loud(0.15, 0.85);
  EXPECT_LT(std::sqrt(run_noise_at(trend.hyper, quiet)), 0.05);
  EXPECT_GT(std::sqrt(run_noise_at(trend.hyper, loud)), 0.08);
  EXPECT_EQ(run_noise_at(flat.hyper, quiet), run_noise_at(flat.hyper, loud));
  // Where the runs are quiet the emulator with the trend is nearer the truth and surer of it.
  double err_trend = 0, err_flat = 0, var_trend = 0, var_flat = 0;
  int inside = 0, n = 0;
  const Eigen::MatrixXd test = latin_square(400, 55);
  for (int i = 0; i < test.rows(); ++i) {
    const Eigen::VectorXd t = test.row(i).transpose();
    if (!(t(1) < t(0) - 0.1)) continue;
    const Prediction a = predict(trend, t), b = predict(flat, t);
    err_trend += std::pow(a.mean - ln_uct(t), 2), err_flat += std::pow(b.mean - ln_uct(t), 2);
    var_trend += a.var, var_flat += b.var;
    inside += std::abs(a.mean - ln_uct(t)) <= 1.645 * std::sqrt(a.var) ? 1 : 0;
    ++n;
  }
  EXPECT_LT(err_trend, err_flat);
  EXPECT_LT(var_trend, 0.5 * var_flat);
  EXPECT_GT(double(inside) / n, 0.75);  // surer, and still honest
  RecordProperty("quiet_sd", std::to_string(std::sqrt(run_noise_at(trend.hyper, quiet))));
  RecordProperty("loud_sd", std::to_string(std::sqrt(run_noise_at(trend.hyper, loud))));
  RecordProperty("rmse_trend", std::to_string(std::sqrt(err_trend / n)));
  RecordProperty("rmse_flat", std::to_string(std::sqrt(err_flat / n)));
  RecordProperty("quiet_coverage", std::to_string(double(inside) / n));
}

// Four points of two runs each, whose runs agree to sd 0.03 but whose means depart from any
// smooth trend over the box by +-0.2 (a pattern lengths of at least the box cannot follow): the
// replicates' spread says the packings' scatter is small, so the misfit is signal, not noise.
// With the means alone the nugget takes the misfit for scatter (what made the seed rock's D/R 49
// checks agree with a vague prediction).
TEST(Emulator, ReplicatesSpreadSetsTheNuggetSoAMisfitBetweenPointsIsNotScatter) {
  Eigen::MatrixXd x(4, 2);
  x << 0, 0, 1, 0, 0, 1, 1, 1;
  GpData d{x, Eigen::Vector4d(0.2, -0.2, -0.2, 0.2), Eigen::VectorXd::Zero(4),
           Eigen::VectorXd::Constant(4, 2.0), Eigen::VectorXd::Constant(4, 0.03 * 0.03)};
  GpOptions o;
  o.min_length = 1.0;
  o.linear_trend = false;
  o.replicate_spread = true;
  const Gp with_runs = fit_gp(d, o);
  o.replicate_spread = false;
  const Gp means_only = fit_gp(d, o);
  EXPECT_LT(std::sqrt(with_runs.hyper.nugget), 0.06);
  EXPECT_GT(std::sqrt(means_only.hyper.nugget), 0.15);
  RecordProperty("run_sd_with_runs", std::to_string(std::sqrt(with_runs.hyper.nugget)));
  RecordProperty("run_sd_means_only", std::to_string(std::sqrt(means_only.hyper.nugget)));
}

TEST(Emulator, BadDataAreRefused) {
  GpData d = noisy(5, 0.01, 1);
  auto message = [](const GpData& data) {
    try {
      fit_gp(data);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  GpData one = d;
  one.x.conservativeResize(1, 2), one.y.conservativeResize(1), one.noise_var.conservativeResize(1);
  EXPECT_EQ(message(one), "emulator: at least 2 points are needed");
  GpData outside = d;
  outside.x(2, 1) = 1.5;
  EXPECT_EQ(message(outside), "emulator: a coordinate outside [0, 1]");
  GpData nan = d;
  nan.y(1) = std::nan("");
  EXPECT_EQ(message(nan), "emulator: a non-finite value in the data");
  GpData short_y = d;
  short_y.y.conservativeResize(4);
  EXPECT_EQ(message(short_y), "emulator: x, y and noise_var differ in length");
  GpData negative = d;
  negative.noise_var(0) = -1;
  EXPECT_EQ(message(negative), "emulator: a negative noise_var");
  GpData no_runs = d;
  no_runs.runs = Eigen::VectorXd::Zero(5);
  EXPECT_EQ(message(no_runs), "emulator: runs must be >= 1 for every point");
  GpData spread = d;
  spread.runs = Eigen::VectorXd::Constant(5, 2.0);
  spread.within_ss = Eigen::VectorXd::Constant(5, -0.1);
  EXPECT_EQ(message(spread), "emulator: within_ss must be >= 0 for every point");
  spread.runs.resize(0);
  spread.within_ss = Eigen::VectorXd::Zero(5);
  EXPECT_EQ(message(spread), "emulator: within_ss needs the points' runs");
  // A noise slope whose length is not the data's dimension.
  GpHyper slope = fit_gp(d).hyper;
  slope.noise_slope = Eigen::VectorXd::Zero(3);
  try {
    condition_gp(d, slope);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "emulator: noise_slope must have one entry per dimension or none");
  }
}

}  // namespace
}  // namespace rockcal::inference
