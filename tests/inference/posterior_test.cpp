// Focus: the posterior and its credible region. With emulators that know the function, the region
// holds the truth, is bounded inside the box, shrinks with the lab's uncertainty and reaches the
// box's edge (not bounded) when a target lies beyond what the box can reach.
#include <gtest/gtest.h>

#include "orchestrator/inference/posterior/feasibility.hpp"
#include "orchestrator/inference/posterior/region.hpp"
#include "test_functions.hpp"

namespace rockcal::inference {
namespace {

using testing::latin_square;
using testing::ln_btt;
using testing::ln_uct;

struct Pair {
  Gp uct, btt;
  std::vector<const Gp*> both() const { return {&uct, &btt}; }
};

Pair exact_emulators() {
  const Eigen::MatrixXd x = latin_square(40, 11);
  GpData u{x, Eigen::VectorXd(40), Eigen::VectorXd::Constant(40, 1e-6), {}, {}}, b = u;
  for (int i = 0; i < 40; ++i) {
    u.y(i) = ln_uct(x.row(i).transpose());
    b.y(i) = ln_btt(x.row(i).transpose());
  }
  return {fit_gp(u), fit_gp(b)};
}

std::vector<Target> targets_at(const Eigen::VectorXd& truth, double sd) {
  return {{ln_uct(truth), sd, 0.0}, {ln_btt(truth), sd, 0.0}};
}

TEST(Posterior, TheRegionHoldsTheTruthAndIsBoundedInsideTheBox) {
  const Pair e = exact_emulators();
  const Eigen::Vector2d truth(0.45, 0.6);
  const std::vector<Target> t = targets_at(truth, 0.05);
  const PosteriorGrid g = posterior_on_grid(e.both(), t);
  EXPECT_EQ(g.points.rows(), 81 * 81);
  EXPECT_NEAR(g.weight.sum(), 1.0, 1e-9);
  const Region r = credible_region(g, 0.9);
  EXPECT_TRUE(in_region(g, r, truth));
  EXPECT_TRUE(r.bounded());
  for (int k = 0; k < 2; ++k) {
    EXPECT_LT(r.marginal_lo(k), truth(k));
    EXPECT_GT(r.marginal_hi(k), truth(k));
  }
  const Eigen::VectorXd peak = density_peak(g, e.both(), t);
  EXPECT_NEAR(peak(0), truth(0), 0.02);
  EXPECT_NEAR(peak(1), truth(1), 0.02);
}

// A posterior far narrower than a cell of the whole box: the zoomed grid spans its mass with
// cells as fine as it, holds the truth, keeps the same intervals, and its edges inside the box
// are not the box's bounds.
TEST(Posterior, AZoomedGridResolvesAPosteriorNarrowerThanACellOfTheBox) {
  const Pair e = exact_emulators();
  const Eigen::Vector2d truth(0.43, 0.57);
  const std::vector<Target> t = targets_at(truth, 0.003);
  const PosteriorGrid whole = posterior_on_grid(e.both(), t);
  const PosteriorGrid zoom = zoomed_grid(whole, e.both(), t);
  EXPECT_EQ(zoom.per_dim, whole.per_dim);
  for (int k = 0; k < 2; ++k) {
    EXPECT_GT(zoom.lo(k), 0.0);
    EXPECT_LT(zoom.hi(k), 1.0);
    EXPECT_LT(zoom.hi(k) - zoom.lo(k), 0.25);
    EXPECT_LT(zoom.lo(k), truth(k));
    EXPECT_GT(zoom.hi(k), truth(k));
  }
  const Region r = credible_region(zoom, 0.9), coarse = credible_region(whole, 0.9);
  EXPECT_TRUE(in_region(zoom, r, truth));
  EXPECT_TRUE(r.bounded());  // a zoomed edge is not the box's
  EXPECT_GT(r.cells.size(), 10 * coarse.cells.size());
  for (int k = 0; k < 2; ++k) {
    EXPECT_LT(r.marginal_lo(k), truth(k));
    EXPECT_GT(r.marginal_hi(k), truth(k));
  }
  EXPECT_NEAR(r.mass_fraction_of_box, coarse.mass_fraction_of_box, 0.5 / (81.0 * 81.0) * 50);
  // Outside its span a point falls in no region cell.
  EXPECT_FALSE(in_region(zoom, r, Eigen::Vector2d(0.9, 0.1)));
}

// Where the mass lies at the box's edge the zoomed grid keeps that edge, and the region says so.
TEST(Posterior, AZoomedGridKeepsTheBoxsEdgeWhereTheMassIs) {
  const Pair e = exact_emulators();
  const Eigen::Vector2d truth(0.002, 0.5);
  const std::vector<Target> t = targets_at(truth, 0.01);
  const PosteriorGrid zoom = zoomed_grid(posterior_on_grid(e.both(), t), e.both(), t);
  EXPECT_EQ(zoom.lo(0), 0.0);
  EXPECT_TRUE(credible_region(zoom, 0.9).at_lower[0]);
}

TEST(Posterior, TheRegionShrinksWithTheLabsUncertainty) {
  const Pair e = exact_emulators();
  const Eigen::Vector2d truth(0.5, 0.5);
  const Region wide = credible_region(posterior_on_grid(e.both(), targets_at(truth, 0.10)));
  const Region narrow = credible_region(posterior_on_grid(e.both(), targets_at(truth, 0.02)));
  EXPECT_LT(narrow.mass_fraction_of_box, 0.5 * wide.mass_fraction_of_box);
}

// With few runs the emulators' variance widens the region; the exact-emulator posterior drops it
// and keeps the lab's share, which is what more runs can reach. With exact emulators the two agree.
TEST(Posterior, ExactEmulatorsLeaveOnlyTheLabsUncertainty) {
  const Eigen::Vector2d truth(0.5, 0.5);
  const std::vector<Target> t = targets_at(truth, 0.05);
  const Eigen::MatrixXd x = latin_square(6, 3);
  GpData u{x, Eigen::VectorXd(6), Eigen::VectorXd::Constant(6, 0.04), {}, {}}, b = u;
  for (int i = 0; i < 6; ++i) {
    u.y(i) = ln_uct(x.row(i).transpose());
    b.y(i) = ln_btt(x.row(i).transpose());
  }
  const Gp fu = fit_gp(u), fb = fit_gp(b);
  const PosteriorGrid few = posterior_on_grid({&fu, &fb}, t);
  const PosteriorGrid few_exact = with_exact_emulators(few, t);
  EXPECT_EQ(few_exact.var.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LT(credible_region(few_exact).mass_fraction_of_box,
            0.8 * credible_region(few).mass_fraction_of_box);

  const Pair e = exact_emulators();
  const PosteriorGrid known = posterior_on_grid(e.both(), t);
  EXPECT_NEAR(credible_region(with_exact_emulators(known, t)).mass_fraction_of_box,
              credible_region(known).mass_fraction_of_box,
              0.1 * credible_region(known).mass_fraction_of_box);
  EXPECT_THROW(with_exact_emulators(known, {t[0]}), std::invalid_argument);
}

TEST(Posterior, ATargetBeyondTheBoxPutsTheRegionOnItsEdge) {
  const Pair e = exact_emulators();
  // Both loads far above what the strongest bonds in the box give.
  const std::vector<Target> t = {{ln_uct(Eigen::Vector2d(1, 1)) + 1.0, 0.05, 0.0},
                                 {ln_btt(Eigen::Vector2d(1, 1)) + 1.0, 0.05, 0.0}};
  const Region r = credible_region(posterior_on_grid(e.both(), t));
  EXPECT_FALSE(r.bounded());
  EXPECT_TRUE(r.at_upper[0] || r.at_upper[1]);
}

TEST(Posterior, MismatchedInputsAreRefused) {
  const Pair e = exact_emulators();
  EXPECT_THROW(posterior_on_grid(e.both(), {{0.0, 0.05, 0.0}}), std::invalid_argument);
  EXPECT_THROW(posterior_on_grid(e.both(), {{0.0, 0.0, 0.0}, {0.0, 0.05, 0.0}}),
               std::invalid_argument);
}

}  // namespace
}  // namespace rockcal::inference

namespace rockcal::inference {
namespace {

// Runs that end without a result (no peak) at x > 0.6 and with one below: the chance of a result
// is about the nearest runs' outcome (1 with no runs), halfway between two runs of each kind about
// a half, and the posterior (whose targets lie in the failing half) loses its mass there.
TEST(Feasibility, FailedRunsTakeThePosteriorsMassOutOfTheirZone) {
  RunResults runs;
  runs.x = latin_square(30, 5);
  runs.has_value.resize(30);
  for (int i = 0; i < 30; ++i) runs.has_value(i) = runs.x(i, 0) > 0.6 ? 0.0 : 1.0;
  EXPECT_DOUBLE_EQ(feasibility(RunResults{}, Eigen::Vector2d(0.9, 0.9)), 1.0);
  RunResults one_failure{Eigen::RowVector2d(0.9, 0.9), Eigen::VectorXd::Zero(1)};
  EXPECT_NEAR(feasibility(one_failure, Eigen::Vector2d(0.9, 0.9)), 0.05 / 1.05, 1e-12);
  // Far from the lone failure its outcome still stands: failures come in regions.
  EXPECT_NEAR(feasibility(one_failure, Eigen::Vector2d(0.1, 0.1)), 0.05 / 1.05, 1e-12);
  RunResults pair{Eigen::MatrixXd(2, 2), Eigen::Vector2d(0.0, 1.0)};
  pair.x << 0.4, 0.5, 0.6, 0.5;
  EXPECT_NEAR(feasibility(pair, Eigen::Vector2d(0.5, 0.5)), 1.05 / 2.05, 1e-9);
  EXPECT_LT(feasibility(runs, Eigen::Vector2d(0.9, 0.5)), 0.1);
  EXPECT_GT(feasibility(runs, Eigen::Vector2d(0.2, 0.5)), 0.9);

  const Pair e = exact_emulators();
  // Lab values known to 30%: the plain posterior spreads across the edge.
  const std::vector<Target> t = targets_at(Eigen::Vector2d(0.6, 0.5), 0.3);
  PosteriorGrid g = posterior_on_grid(e.both(), t);
  auto mass_beyond = [](const PosteriorGrid& grid, double edge) {
    double m = 0.0;
    for (Eigen::Index c = 0; c < grid.points.rows(); ++c)
      m += grid.points(c, 0) > edge ? grid.weight(c) : 0.0;
    return m;
  };
  const double plain = mass_beyond(g, 0.65);
  EXPECT_GT(plain, 0.2);
  apply_feasibility(g, runs, t);
  EXPECT_LT(mass_beyond(g, 0.65), plain / 5);
  EXPECT_NEAR(g.weight.sum(), 1.0, 1e-9);
  // The exact-emulator view keeps the feasibility.
  EXPECT_LT(mass_beyond(with_exact_emulators(g, t), 0.65), plain / 5);
  apply_feasibility(g, RunResults{}, t);  // no runs: the plain posterior again
  EXPECT_DOUBLE_EQ(mass_beyond(g, 0.65), plain);
  RecordProperty("mass_beyond_plain", std::to_string(plain));
}

// Where one direction decides the outcome (a strength ratio), the metric measures distance mostly
// along it: a failure then stands far along the other direction, and a success beside it on that
// direction does not blur it. Two resolutions' outcomes overlaid: near the answered resolution's
// runs (by the same metric) its outcomes replace the other's.
TEST(Feasibility, AMetricLetsAnOutcomeHoldAlongTheDirectionThatLeavesItUnchanged) {
  FeasibilitySettings along;
  along.metric = Eigen::Matrix2d{{1.0, 0.0}, {0.0, 1.0 / 16}};  // x decides, y reaches 4x farther
  RunResults runs{Eigen::MatrixXd(2, 2), Eigen::Vector2d(0.0, 1.0)};
  runs.x << 0.7, 0.2, 0.5, 0.5;  // a failure at x 0.7, a success at x 0.5
  // At (0.7, 0.6): 0.4 from the failure, 0.224 from the success. Isotropic, the success is the
  // nearer and the failure's weight exp(-22) leaves it feasible; with the metric the failure is
  // 0.1 away (same x), the success 0.2016, whose weight exp(-0.5 (0.040625 - 0.01) / 0.05^2)
  // leaves the point about as infeasible as at the failure itself.
  const Eigen::Vector2d x(0.7, 0.6);
  EXPECT_GT(feasibility(runs, x), 0.999);
  const double w = std::exp(-0.5 * (0.040625 - 0.01) / 0.0025);
  EXPECT_NEAR(feasibility(runs, x, along), (w + 0.05) / (1 + w + 0.05), 1e-9);
  EXPECT_LT(feasibility(runs, x, along), 0.05);
  EXPECT_NEAR(squared_distances(runs.x, x, along)(0), 0.01, 1e-12);

  // The coarse success at (0.7, 0.45) lies 0.0625 from the fine failure at (0.7, 0.2) under the
  // metric: replaced. The coarse failure at (0.3, 0.9) is 0.224 from the fine success at (0.5,
  // 0.5) and farther from the failure: kept.
  RunResults coarse{Eigen::MatrixXd(2, 2), Eigen::Vector2d(1.0, 0.0)};
  coarse.x << 0.7, 0.45, 0.3, 0.9;
  const RunResults both = overlaid(coarse, runs, 0.1, along);
  ASSERT_EQ(both.x.rows(), 3);
  EXPECT_EQ(both.x.row(0), Eigen::RowVector2d(0.3, 0.9));
  EXPECT_EQ(both.has_value, Eigen::Vector3d(0.0, 0.0, 1.0));
  EXPECT_EQ(overlaid(coarse, runs, 0.1).x.rows(), 4);  // isotropic: 0.206 and 0.45 away, kept
}

}  // namespace
}  // namespace rockcal::inference
