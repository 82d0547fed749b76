// A Gaussian-process emulator of one observable over normalised parameters (the unit cube).
//
// Why: a DEM run is dear and noisy (each packing's peak load scatters by tens of per cent at small
// specimens), so no single run says what a point's mean load is. The emulator pools every run:
// its mean is the best estimate of the ensemble-mean observable anywhere in the box and its
// variance says how well the runs so far pin it, which is what a posterior needs to be honest.
//
// The model (universal kriging): y(x) = h(x)'beta + f(x) + noise, with
//   h(x) = (1, x_1, ..., x_d): a linear trend, which in log space is the measured homogeneity of
//          the loads in the strengths (ln load ~ a + sum_k p_k ln F_k), fitted by generalised least
//          squares and its uncertainty carried into the predictive variance;
//   f ~ GP(0, s2 * Matern52_ARD(x, x'; lengths)): the departure from it;
//   noise_i ~ N(0, noise_var_i + nugget(x_i) / runs_i): nugget(x) is one run's scatter (the
//          packings' scatter) at x, over the point's number of runs (a point of many realisations
//          is known better); noise_var_i a known extra variance of the point (0 for the
//          calibration's runs).
// The scatter is not one number for the box: a bonded specimen whose shear bonds are the weaker
// fails along them in nearly the same way on every packing (a UCT's ln load scatters by about 2%
// where F_s0 < F_r0 against 10% beyond), so with GpOptions::noise_trend ln nugget(x) is linear in
// x, ln nugget(x) = ln nugget + slope . (x - 0.5): one run's variance at the box's centre and how
// it changes across the box (a heteroscedastic GP with a log-linear noise model). A Gaussian prior
// on the slope keeps it near 0 where the runs do not show a change. Hyperparameters (lengths, s2,
// nugget, slope) maximise the restricted likelihood (NLopt, bounded) of the points' means, times,
// when the data carry within_ss, that of each point's runs about their mean, which depends on the
// noise model alone (within_ss_i ~ nugget(x_i) chi^2 with runs_i - 1 degrees of freedom).
#pragma once

#include <memory>
#include <span>
#include <vector>

#include <Eigen/Dense>

namespace rockcal::inference {

// The training data: one row per distinct point. y is the mean of the observable over the point's
// runs, runs how many there were, noise_var a known extra variance of that mean (usually 0).
struct GpData {
  Eigen::MatrixXd x;          // n x d, each coordinate in [0, 1]
  Eigen::VectorXd y;          // n
  Eigen::VectorXd noise_var;  // n, >= 0
  Eigen::VectorXd runs;       // n, >= 1; empty: one run each
  // n: the sum of squared deviations of the point's runs from their mean y (0 for one run);
  // empty: the means alone (what is known of the runs' spread is then not used).
  Eigen::VectorXd within_ss;
};

struct GpHyper {
  Eigen::VectorXd length;  // d correlation lengths, in units of the box
  double signal_var = 1.0;
  double nugget = 1e-6;  // one run's noise variance (at the box's centre when noise_slope is set)
  // d: d ln nugget / dx (GpOptions::noise_trend); empty: one run's variance is the nugget anywhere.
  Eigen::VectorXd noise_slope;
};

// One run's noise variance at x: nugget * exp(noise_slope . (x - 0.5)).
double run_noise_at(const GpHyper& hyper, const Eigen::VectorXd& x);

struct GpOptions {
  double min_length = 0.2;  // shorter chases the runs' scatter as if it were signal
  double max_length = 3.0;  // longer is a straight line over the box: the trend's job
  double min_nugget = 1e-8;
  int restarts = 3;          // extra starts of the likelihood search beyond the default one
  bool linear_trend = true;  // false: a constant trend whatever the number of points
  // The replicates' spread about their points' means enters the likelihood (data.within_ss; off:
  // fit_gp drops it, and the likelihood is that of the means).
  // Where the lengths are held long (the two-level discrepancy, whose few points a smooth trend
  // cannot always follow) the means alone let the misfit between points pass for the packings'
  // scatter. Off for the coarse emulators, whose short lengths take a misfit as signal: there a
  // few replicates' spread (4 degrees of freedom after 14 runs) pulled the nugget down by chance
  // and a formula twin's search stopped sure of a region its check runs then contradicted (z 4.9).
  bool replicate_spread = false;
  // One run's scatter changes across the box (log-linear in x, see the model above); off: one
  // nugget for the box (the discrepancy emulator's few points cannot tell a slope).
  bool noise_trend = false;
  double max_noise_slope = 5.0;       // |d ln nugget / dx| per axis: e^5 = 150 across the box
  double noise_slope_prior_sd = 2.0;  // a run's variance 7x apart across the box is 1 sd
};

struct Prediction {
  double mean = 0.0;
  double var = 0.0;  // of the latent mean (noise excluded), with the trend's uncertainty
};

// A fitted emulator: the data, the hyperparameters and the factorised covariance.
struct Gp {
  GpData data;
  GpHyper hyper;
  int trend_terms = 1;    // 1 (a constant) or d + 1 (linear), by how many points there are
  Eigen::MatrixXd trend;  // H: n x trend_terms
  Eigen::LLT<Eigen::MatrixXd> chol;  // of K = s2 R + diag(noise_var + nugget / runs)
  Eigen::VectorXd beta;              // the trend's GLS coefficients
  Eigen::VectorXd alpha;             // K^-1 (y - H beta)
  Eigen::MatrixXd h_kinv_h_inv;      // (H' K^-1 H)^-1
  double log_likelihood = 0.0;       // the restricted log-likelihood at the hyperparameters
  // Set on a discrepancy emulator (two_level.hpp): this GP models y minus `base`'s mean, and its
  // predictions add `base`'s mean and variance.
  std::shared_ptr<const Gp> base;
};

// Fits the hyperparameters and factorises. Needs at least 2 points; throws std::invalid_argument
// on mismatched sizes, coordinates outside [0, 1] or non-finite values.
Gp fit_gp(GpData data, const GpOptions& options = {});
// Factorises at given hyperparameters (no search): what fantasies and tests use.
Gp condition_gp(GpData data, const GpHyper& hyper);

Prediction predict(const Gp& gp, const Eigen::VectorXd& x);
// The same at every row of `points` (m x d) at once: means and variances, m each. Both include
// the base emulator's when the GP has one.
void predict_many(const Gp& gp, const Eigen::MatrixXd& points, Eigen::VectorXd& mean,
                  Eigen::VectorXd& var);
// The mean alone at x (d coordinates), without allocating: what a search over the emulator's mean
// calls thousands of times.
double predict_mean(const Gp& gp, std::span<const double> x);
// The prior covariance matrix between the rows of a (m x d) and of b (p x d).
Eigen::MatrixXd cross_covariance(const Gp& gp, const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

}  // namespace rockcal::inference
