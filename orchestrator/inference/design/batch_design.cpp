#include "orchestrator/inference/design/batch_design.hpp"

#include "orchestrator/inference/posterior/region.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace rockcal::inference {
namespace {

// One target's emulator with the pending runs added as observations of one run's variance at
// their points (their values do not enter the variance).
struct Conditioned {
  Eigen::MatrixXd x;  // training rows then pending rows
  Eigen::LLT<Eigen::MatrixXd> chol;
};

Conditioned condition(const Gp& gp, const Eigen::MatrixXd& pending) {
  Conditioned c{Eigen::MatrixXd(gp.data.x.rows() + pending.rows(), gp.data.x.cols()), {}};
  c.x << gp.data.x, pending;
  Eigen::MatrixXd k = cross_covariance(gp, c.x, c.x);
  const int n = int(gp.data.x.rows());
  for (int i = 0; i < c.x.rows(); ++i) {
    const double runs = i < n && gp.data.runs.size() ? gp.data.runs(i) : 1.0;
    k(i, i) += (i < n ? gp.data.noise_var(i) : 0.0) +
               run_noise_at(gp.hyper, c.x.row(i).transpose()) / runs + 1e-10 * gp.hyper.signal_var;
  }
  c.chol.compute(k);
  return c;
}

}  // namespace

std::vector<DesignChoice> choose_batch(const DesignInput& in) {
  if (!in.posterior || in.emulators.size() != in.targets.size() || in.candidates.rows() == 0)
    throw std::invalid_argument("design: emulators, targets and candidates must agree");
  const PosteriorGrid& post = *in.posterior;
  const std::vector<int> ref = densest_cells(post, in.reference_cells);
  Eigen::MatrixXd g(ref.size(), post.dims);
  Eigen::VectorXd w(ref.size());
  for (std::size_t r = 0; r < ref.size(); ++r) {
    g.row(r) = post.points.row(ref[r]);
    w(r) = post.weight(ref[r]);
  }
  w /= w.sum();
  Eigen::MatrixXd pending = in.pending;
  if (pending.cols() != post.dims) pending.resize(0, post.dims);
  std::vector<DesignChoice> out;
  const int c = int(in.candidates.rows());
  std::vector<bool> taken(std::size_t(c), false);
  for (int pick = 0; pick < in.batch && (!in.distinct || pick < c); ++pick) {
    Eigen::VectorXd score = Eigen::VectorXd::Zero(c);
    for (std::size_t j = 0; j < in.emulators.size(); ++j) {
      const Gp& gp = *in.emulators[j];
      const Conditioned cond = condition(gp, pending);
      const Eigen::MatrixXd kxg = cross_covariance(gp, cond.x, g);              // n x m
      const Eigen::MatrixXd kxc = cross_covariance(gp, cond.x, in.candidates);  // n x c
      const Eigen::MatrixXd a = cond.chol.solve(kxg);
      const Eigen::MatrixXd b = cond.chol.solve(kxc);
      const Eigen::MatrixXd cov = cross_covariance(gp, g, in.candidates) - a.transpose() * kxc;
      Eigen::VectorXd var_g(g.rows()), var_c(c);
      for (int r = 0; r < g.rows(); ++r)
        var_g(r) = std::max(0.0, gp.hyper.signal_var - kxg.col(r).dot(a.col(r)));
      for (int k = 0; k < c; ++k)
        var_c(k) = std::max(0.0, gp.hyper.signal_var - kxc.col(k).dot(b.col(k)));
      const Target& t = in.targets[j];
      const double lab = t.sd * t.sd + t.discrepancy_sd * t.discrepancy_sd;
      // Weight of a variance reduction at reference cell r: w_r / (lab + var_r).
      const Eigen::VectorXd weight = w.array() / (lab + var_g.array());
      for (int k = 0; k < c; ++k) {
        const double tau2 = run_noise_at(gp.hyper, in.candidates.row(k).transpose());
        score(k) += weight.dot(cov.col(k).cwiseAbs2()) / (var_c(k) + tau2);
      }
    }
    // A run where runs end without a result teaches the emulators nothing: its worth is its
    // shrinkage times the chance that it gives one (the posterior's feasibility).
    if (post.log_feasibility.size() == post.points.rows()) {
      for (int k = 0; k < c; ++k) {
        const int cell = cell_of(post, in.candidates.row(k).transpose());
        score(k) *= std::exp(post.log_feasibility(cell));
      }
    }
    if (in.distinct) {
      for (int k = 0; k < c; ++k) {
        if (taken[std::size_t(k)]) score(k) = -1.0;  // every untaken score is >= 0
      }
    }
    Eigen::Index best = 0;
    score.maxCoeff(&best);
    taken[std::size_t(best)] = true;
    out.push_back({int(best), score(best)});
    pending.conservativeResize(pending.rows() + 1, Eigen::NoChange);
    pending.row(pending.rows() - 1) = in.candidates.row(best);
  }
  return out;
}

std::vector<double> emulator_share(const PosteriorGrid& posterior,
                                   const std::vector<Target>& targets) {
  std::vector<double> out;
  for (std::size_t j = 0; j < targets.size(); ++j) {
    const Target& t = targets[j];
    const double lab = t.sd * t.sd + t.discrepancy_sd * t.discrepancy_sd;
    out.push_back(posterior.weight.dot(posterior.var.col(j)) / lab);
  }
  return out;
}

}  // namespace rockcal::inference
