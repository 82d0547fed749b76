// Focus: the two-resolution emulator. With many coarse runs and a handful of fine ones, it predicts
// the fine observable far better than the fine runs alone can, its band covers the fine truth,
// and its variance holds the coarse emulator's as well as its own.
#include <gtest/gtest.h>

#include <random>

#include "orchestrator/inference/emulator/two_level.hpp"
#include "test_functions.hpp"

namespace rockcal::inference {
namespace {

using testing::latin_square;
using testing::ln_uct;

// The fine specimen: the coarse load shifted by a smooth resolution factor (+0.25 to +0.35 in ln).
double ln_fine(const Eigen::VectorXd& x) {
  return ln_uct(x) + 0.25 + 0.1 * x(0);
}

GpData runs(int n, unsigned seed, double sd, bool fine) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sd);
  GpData d{latin_square(n, seed), Eigen::VectorXd(n), Eigen::VectorXd::Zero(n), {}, {}};
  for (int i = 0; i < n; ++i) {
    const Eigen::VectorXd x = d.x.row(i).transpose();
    d.y(i) = (fine ? ln_fine(x) : ln_uct(x)) + noise(rng);
  }
  return d;
}

TEST(TwoLevelEmulator, AFewFineRunsOnACoarseEmulatorPredictTheFineObservable) {
  double sq_two = 0.0, sq_alone = 0.0, sq_coarse = 0.0;
  int inside = 0, total = 0;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const Gp coarse = fit_gp(runs(80, seed, 0.15, false));
    const GpData fine = runs(8, 50 + seed, 0.08, true);
    const Gp two = fit_two_level(coarse, fine);
    const Gp alone = fit_gp(fine);
    ASSERT_TRUE(two.base);
    const Eigen::MatrixXd test = latin_square(50, 200 + seed);
    Eigen::VectorXd m2, v2, ma, va, mc, vc;
    predict_many(two, test, m2, v2);
    predict_many(alone, test, ma, va);
    predict_many(coarse, test, mc, vc);
    for (int i = 0; i < test.rows(); ++i) {
      const double truth = ln_fine(test.row(i).transpose());
      sq_two += std::pow(m2(i) - truth, 2);
      sq_alone += std::pow(ma(i) - truth, 2);
      sq_coarse += std::pow(mc(i) - ln_uct(test.row(i).transpose()), 2);
      inside += std::abs(m2(i) - truth) <= 1.645 * std::sqrt(v2(i)) ? 1 : 0;
      ++total;
      EXPECT_GE(v2(i), vc(i));  // never surer than the coarse emulator it stands on
    }
  }
  const double rms_two = std::sqrt(sq_two / total), rms_alone = std::sqrt(sq_alone / total);
  std::printf("rms two-level %.3f, fine runs alone %.3f, coarse %.3f, 90%% band coverage %.2f\n",
              rms_two, rms_alone, std::sqrt(sq_coarse / total), double(inside) / total);
  EXPECT_LT(rms_two, 0.08);
  EXPECT_LT(rms_two, 0.75 * rms_alone);
  EXPECT_GT(double(inside) / total, 0.75);
}

// Four fine points of two runs each that agree to sd 0.03, on a discrepancy from the coarse
// emulator that alternates by +-0.2 over the box (the seed rock's fine UCT: 1.5x the coarse at one
// end of the valley, 0.8x at the other): the replicates' spread keeps the nugget at the runs'
// scatter, so the misfit shows as the emulator's variance, not as one run's noise.
TEST(TwoLevelEmulator, TheFineRunsReplicatesSetOneFineRunsScatter) {
  const Gp coarse = fit_gp(runs(80, 3, 0.15, false));
  GpData fine{Eigen::MatrixXd(4, 2), Eigen::VectorXd(4), Eigen::VectorXd::Zero(4),
              Eigen::VectorXd::Constant(4, 2.0), Eigen::VectorXd::Constant(4, 0.03 * 0.03)};
  fine.x << 0.1, 0.1, 0.9, 0.1, 0.1, 0.9, 0.9, 0.9;
  const double shift[] = {0.2, -0.2, -0.2, 0.2};
  for (int i = 0; i < 4; ++i) fine.y(i) = ln_fine(fine.x.row(i).transpose()) + shift[i];
  const Gp two = fit_two_level(coarse, fine);
  EXPECT_LT(std::sqrt(two.hyper.nugget), 0.06);
  RecordProperty("fine_run_sd", std::to_string(std::sqrt(two.hyper.nugget)));
}

TEST(TwoLevelEmulator, MismatchedDataAreRefused) {
  const Gp coarse = fit_gp(runs(20, 3, 0.1, false));
  GpData three_d{latin_square(5, 4, 3), Eigen::VectorXd::Zero(5), Eigen::VectorXd::Zero(5), {}, {}};
  try {
    fit_two_level(coarse, three_d);
    FAIL() << "a 3-D fine set on a 2-D coarse emulator was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "emulator: the fine and coarse data differ in dimension");
  }
  GpData short_noise = runs(5, 5, 0.1, true);
  short_noise.noise_var.resize(2);
  try {
    fit_two_level(coarse, short_noise);
    FAIL() << "a noise_var of the wrong length was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "emulator: x, y and noise_var differ in length");
  }
}

}  // namespace
}  // namespace rockcal::inference
