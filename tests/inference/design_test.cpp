// Focus: the batch design. It picks where the posterior is, counts the pending runs so that a
// batch is not the same run repeated blindly, returns as many runs as asked (each candidate once
// when asked for distinct points), and values a run by what the emulator does not yet know against
// one run's scatter.
#include <gtest/gtest.h>

#include "orchestrator/inference/design/batch_design.hpp"
#include "orchestrator/inference/posterior/region.hpp"
#include "test_functions.hpp"

namespace rockcal::inference {
namespace {

using testing::latin_square;
using testing::ln_btt;
using testing::ln_uct;

struct Fitted {
  Gp uct, btt;
  std::vector<Target> targets;
  PosteriorGrid post;
};

// `run_noise`: one more run's variance (the emulators' nugget, set after the fit).
Fitted setup(int runs, double noise_var, double run_noise = 1e-4) {
  const Eigen::MatrixXd x = latin_square(runs, 5);
  GpData u{x, Eigen::VectorXd(runs), Eigen::VectorXd::Constant(runs, noise_var), {}, {}}, b = u;
  for (int i = 0; i < runs; ++i) {
    u.y(i) = ln_uct(x.row(i).transpose());
    b.y(i) = ln_btt(x.row(i).transpose());
  }
  Fitted s{fit_gp(u), fit_gp(b), {}, {}};
  for (Gp* gp : {&s.uct, &s.btt}) {
    GpHyper h = gp->hyper;
    h.nugget = run_noise;
    *gp = condition_gp(gp->data, h);
  }
  const Eigen::Vector2d truth(0.7, 0.3);
  s.targets = {{ln_uct(truth), 0.03, 0.0}, {ln_btt(truth), 0.03, 0.0}};
  s.post = posterior_on_grid({&s.uct, &s.btt}, s.targets);
  return s;
}

DesignInput input(const Fitted& s, const Eigen::MatrixXd& candidates, int batch) {
  DesignInput in;
  in.emulators = {&s.uct, &s.btt};
  in.targets = s.targets;
  in.posterior = &s.post;
  in.candidates = candidates;
  in.batch = batch;
  return in;
}

TEST(BatchDesign, PicksWhereThePosteriorIsAndCountsPendingRuns) {
  const Fitted s = setup(8, 1e-4);
  const Eigen::MatrixXd cand = latin_square(300, 9);
  const std::vector<DesignChoice> picks = choose_batch(input(s, cand, 4));
  ASSERT_EQ(picks.size(), 4u);
  const Region r = credible_region(s.post, 0.99);
  for (const DesignChoice& p : picks) {
    const Eigen::VectorXd x = cand.row(p.candidate).transpose();
    EXPECT_TRUE(in_region(s.post, r, x) || (x - Eigen::Vector2d(0.7, 0.3)).norm() < 0.3) << x;
  }
  // Pending runs count: each pick is worth less than the one before it (a second run at the
  // same place is a further realisation there, worth what it still removes).
  for (std::size_t i = 1; i < picks.size(); ++i) EXPECT_LT(picks[i].value, picks[i - 1].value);
  // A run already pending at the first pick lowers that candidate's value.
  DesignInput again = input(s, cand, 1);
  again.pending = cand.row(picks[0].candidate);
  EXPECT_LT(choose_batch(again).front().value, picks[0].value);
}

TEST(BatchDesign, ARunIsWorthLittleWhereTheEmulatorAlreadyKnows) {
  const Eigen::MatrixXd cand = latin_square(200, 9);
  const double few = choose_batch(input(setup(6, 1e-4), cand, 1)).front().value;
  const double many = choose_batch(input(setup(60, 1e-4), cand, 1)).front().value;
  EXPECT_LT(many, 0.1 * few);
  // Loud runs (one run's scatter 0.3 in ln, a small specimen's BTT) are worth less than quiet ones.
  const double loud = choose_batch(input(setup(6, 1e-4, 0.09), cand, 1)).front().value;
  EXPECT_LT(loud, few);
}

TEST(BatchDesign, TheEmulatorsShareFallsAsRunsAccumulate) {
  const Fitted few = setup(6, 1e-4);
  const Fitted many = setup(40, 1e-4);
  const std::vector<double> a = emulator_share(few.post, few.targets);
  const std::vector<double> b = emulator_share(many.post, many.targets);
  EXPECT_LT(b[0], a[0]);
  EXPECT_LT(b[1], a[1]);
  EXPECT_LT(b[0], 0.25);
}

// `distinct`: no candidate twice (the first runs of a new emulator need distinct points), and no
// more picks than candidates; without it the same two candidates give a replicate.
TEST(BatchDesign, ADistinctBatchPicksEachCandidateOnce) {
  const Fitted s = setup(8, 1e-4, 0.09);
  Eigen::MatrixXd two(2, 2);
  two << 0.7, 0.3, 0.1, 0.9;
  const std::vector<DesignChoice> replicated = choose_batch(input(s, two, 3));
  ASSERT_EQ(replicated.size(), 3u);
  DesignInput in = input(s, two, 3);
  in.distinct = true;
  const std::vector<DesignChoice> picks = choose_batch(in);
  ASSERT_EQ(picks.size(), 2u);
  EXPECT_NE(picks[0].candidate, picks[1].candidate);
}

TEST(BatchDesign, MismatchedInputsAreRefused) {
  const Fitted s = setup(8, 1e-4);
  DesignInput in = input(s, latin_square(10, 1), 1);
  in.targets.pop_back();
  EXPECT_THROW(choose_batch(in), std::invalid_argument);
}

}  // namespace
}  // namespace rockcal::inference
