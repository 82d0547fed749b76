#include "orchestrator/inference/emulator/gp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <nlopt.hpp>

namespace rockcal::inference {
namespace {

Eigen::VectorXd trend_row(const Eigen::VectorXd& x, int terms) {
  Eigen::VectorXd h(terms);
  h(0) = 1.0;
  for (int k = 1; k < terms; ++k) h(k) = x(k - 1);
  return h;
}

Eigen::MatrixXd trend_matrix(const Eigen::MatrixXd& x, int terms) {
  Eigen::MatrixXd h(x.rows(), terms);
  for (int i = 0; i < x.rows(); ++i) h.row(i) = trend_row(x.row(i).transpose(), terms).transpose();
  return h;
}

// A linear trend needs a few points beyond its d + 1 coefficients to leave the GP anything.
int trend_terms_for(const GpData& d) {
  const int dims = int(d.x.cols());
  return d.x.rows() >= 2 * (dims + 1) ? dims + 1 : 1;
}

void check(const GpData& d) {
  const auto n = d.x.rows();
  if (n < 2) throw std::invalid_argument("emulator: at least 2 points are needed");
  if (d.y.size() != n || d.noise_var.size() != n)
    throw std::invalid_argument("emulator: x, y and noise_var differ in length");
  if (!d.x.allFinite() || !d.y.allFinite() || !d.noise_var.allFinite())
    throw std::invalid_argument("emulator: a non-finite value in the data");
  if (d.x.minCoeff() < -1e-12 || d.x.maxCoeff() > 1 + 1e-12)
    throw std::invalid_argument("emulator: a coordinate outside [0, 1]");
  if (d.noise_var.minCoeff() < 0) throw std::invalid_argument("emulator: a negative noise_var");
  if (d.runs.size() != 0 && (d.runs.size() != n || !d.runs.allFinite() || d.runs.minCoeff() < 1))
    throw std::invalid_argument("emulator: runs must be >= 1 for every point");
  if (d.within_ss.size() != 0 &&
      (d.within_ss.size() != n || !d.within_ss.allFinite() || d.within_ss.minCoeff() < 0))
    throw std::invalid_argument("emulator: within_ss must be >= 0 for every point");
  if (d.within_ss.size() != 0 && d.runs.size() == 0)
    throw std::invalid_argument("emulator: within_ss needs the points' runs");
}

// The log-likelihood of each point's runs about their mean: sum_i of ln N-chi^2 terms with
// runs_i - 1 degrees of freedom and the point's one-run variance (the constant in the runs'
// counts left out).
double within_log_likelihood(const GpData& d, const GpHyper& hyper) {
  double ll = 0.0;
  for (Eigen::Index i = 0; i < d.within_ss.size(); ++i) {
    const double dof = d.runs(i) - 1.0;
    if (dof <= 0) continue;
    const double v = run_noise_at(hyper, d.x.row(i).transpose());
    ll -= 0.5 * (dof * std::log(2.0 * std::numbers::pi * v) + d.within_ss(i) / v);
  }
  return ll;
}

// Factorises at `hyper`; returns false when K is not positive definite.
bool factorise(Gp& gp) {
  const GpData& d = gp.data;
  const int n = int(d.x.rows());
  Eigen::MatrixXd k = cross_covariance(gp, d.x, d.x);
  for (int i = 0; i < n; ++i) {
    const double runs = d.runs.size() ? d.runs(i) : 1.0;
    k(i, i) += d.noise_var(i) + run_noise_at(gp.hyper, d.x.row(i).transpose()) / runs +
               1e-10 * gp.hyper.signal_var;
  }
  gp.chol.compute(k);
  if (gp.chol.info() != Eigen::Success) return false;
  gp.trend = trend_matrix(d.x, gp.trend_terms);
  const Eigen::MatrixXd& h = gp.trend;
  const Eigen::MatrixXd kinv_h = gp.chol.solve(h);
  const Eigen::MatrixXd hkh = h.transpose() * kinv_h;
  Eigen::LDLT<Eigen::MatrixXd> hkh_f(hkh);
  if (hkh_f.info() != Eigen::Success || !(hkh_f.vectorD().minCoeff() > 0)) return false;
  gp.h_kinv_h_inv = hkh_f.solve(Eigen::MatrixXd::Identity(hkh.rows(), hkh.cols()));
  gp.beta = gp.h_kinv_h_inv * (kinv_h.transpose() * d.y);
  const Eigen::VectorXd r = d.y - h * gp.beta;
  gp.alpha = gp.chol.solve(r);
  const Eigen::MatrixXd l = gp.chol.matrixL();
  const double log_det_k = 2.0 * l.diagonal().array().log().sum();
  const double log_det_hkh = hkh_f.vectorD().array().log().sum();
  const int p = gp.trend_terms;
  gp.log_likelihood = -0.5 * (r.dot(gp.alpha) + log_det_k + log_det_hkh +
                              (n - p) * std::log(2.0 * std::numbers::pi)) +
                      within_log_likelihood(d, gp.hyper);
  return std::isfinite(gp.log_likelihood);
}

struct Search {
  Gp* gp;
  int dims;
  double slope_prior_sd;
};

// theta = (ln length_1..d, ln signal_var, ln nugget[, noise slope_1..d])
double negative_likelihood(unsigned, const double* theta, double*, void* data) {
  auto* s = static_cast<Search*>(data);
  GpHyper& h = s->gp->hyper;
  for (int k = 0; k < s->dims; ++k) h.length(k) = std::exp(theta[k]);
  h.signal_var = std::exp(theta[s->dims]);
  h.nugget = std::exp(theta[s->dims + 1]);
  double prior = 0.0;
  for (int k = 0; k < int(h.noise_slope.size()); ++k) {
    h.noise_slope(k) = theta[s->dims + 2 + k];
    prior += 0.5 * std::pow(h.noise_slope(k) / s->slope_prior_sd, 2);
  }
  if (!factorise(*s->gp)) return 1e30;
  return -s->gp->log_likelihood + prior;
}

}  // namespace

Gp condition_gp(GpData data, const GpHyper& hyper) {
  check(data);
  if (hyper.noise_slope.size() != 0 && hyper.noise_slope.size() != data.x.cols())
    throw std::invalid_argument("emulator: noise_slope must have one entry per dimension or none");
  Gp gp;
  gp.trend_terms = trend_terms_for(data);
  gp.data = std::move(data);
  gp.hyper = hyper;
  if (!factorise(gp)) throw std::runtime_error("emulator: the covariance is not positive definite");
  return gp;
}

Gp fit_gp(GpData data, const GpOptions& options) {
  check(data);
  const int dims = int(data.x.cols());
  Gp gp;
  gp.trend_terms = options.linear_trend ? trend_terms_for(data) : 1;
  if (!options.replicate_spread) data.within_ss.resize(0);
  gp.data = std::move(data);
  gp.hyper.length = Eigen::VectorXd::Constant(dims, 0.5);
  // The scale of what the trend leaves: the signal variance is searched around it.
  const Eigen::MatrixXd h = trend_matrix(gp.data.x, gp.trend_terms);
  const Eigen::VectorXd coef = h.colPivHouseholderQr().solve(gp.data.y);
  const double spread = std::max(1e-6, (gp.data.y - h * coef).squaredNorm() / gp.data.y.size() +
                                           1e-4 * gp.data.y.array().square().mean());
  std::vector<double> lo, hi;
  for (int k = 0; k < dims; ++k) {
    lo.push_back(std::log(options.min_length));
    hi.push_back(std::log(options.max_length));
  }
  lo.push_back(std::log(1e-4 * spread));
  hi.push_back(std::log(1e2 * spread));
  lo.push_back(std::log(options.min_nugget));
  hi.push_back(std::log(10 * spread));
  const int slopes = options.noise_trend ? dims : 0;
  gp.hyper.noise_slope = Eigen::VectorXd::Zero(slopes);
  for (int k = 0; k < slopes; ++k) {
    lo.push_back(-options.max_noise_slope);
    hi.push_back(options.max_noise_slope);
  }

  Search search{&gp, dims, options.noise_slope_prior_sd};
  nlopt::opt opt(nlopt::LN_BOBYQA, unsigned(dims + 2 + slopes));
  opt.set_lower_bounds(lo);
  opt.set_upper_bounds(hi);
  opt.set_min_objective(negative_likelihood, &search);
  opt.set_xtol_rel(1e-4);
  opt.set_maxeval(300);
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> best_theta;
  const double starts[] = {0.5, 0.2, 1.5, 4.0};
  for (int s = 0; s <= std::min(options.restarts, 3); ++s) {
    std::vector<double> theta(dims + 2 + slopes, 0.0);
    for (int k = 0; k < dims; ++k) theta[k] = std::clamp(std::log(starts[s]), lo[k], hi[k]);
    theta[dims] = std::log(spread);
    theta[dims + 1] = std::clamp(std::log(1e-2 * spread), lo[dims + 1], hi[dims + 1]);
    double value = 0.0;
    try {
      opt.optimize(theta, value);
    } catch (const std::exception&) {
      value = negative_likelihood(0, theta.data(), nullptr, &search);
    }
    if (value < best) best = value, best_theta = theta;
  }
  if (best_theta.empty() || !(best < 1e29))
    throw std::runtime_error("emulator: no hyperparameters give a positive-definite covariance");
  negative_likelihood(0, best_theta.data(), nullptr, &search);
  return gp;
}

double run_noise_at(const GpHyper& hyper, const Eigen::VectorXd& x) {
  if (hyper.noise_slope.size() == 0) return hyper.nugget;
  return hyper.nugget *
         std::exp(hyper.noise_slope.dot(x - Eigen::VectorXd::Constant(x.size(), 0.5)));
}

Eigen::MatrixXd cross_covariance(const Gp& gp, const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  // Squared scaled distances as |a|^2 + |b|^2 - 2 a.b, all at once (the design calls this on
  // hundreds of points per pick).
  const Eigen::RowVectorXd inv = gp.hyper.length.cwiseInverse().transpose();
  const Eigen::MatrixXd as = a.array().rowwise() * inv.array();
  const Eigen::MatrixXd bs = b.array().rowwise() * inv.array();
  Eigen::MatrixXd r2 = (-2.0 * as * bs.transpose()).eval();
  r2.colwise() += as.rowwise().squaredNorm();
  r2.rowwise() += bs.rowwise().squaredNorm().transpose();
  const Eigen::ArrayXXd r = r2.array().max(0.0).sqrt();
  const Eigen::ArrayXXd s5r = std::sqrt(5.0) * r;
  return (gp.hyper.signal_var * (1.0 + s5r + (5.0 / 3.0) * r * r) * (-s5r).exp()).matrix();
}

void predict_many(const Gp& gp, const Eigen::MatrixXd& points, Eigen::VectorXd& mean,
                  Eigen::VectorXd& var) {
  const Eigen::MatrixXd k = cross_covariance(gp, gp.data.x, points);  // n x m
  const Eigen::MatrixXd kinv_k = gp.chol.solve(k);
  const Eigen::MatrixXd h = trend_matrix(points, gp.trend_terms);           // m x p
  const Eigen::MatrixXd u = h.transpose() - gp.trend.transpose() * kinv_k;  // p x m
  mean = h * gp.beta + k.transpose() * gp.alpha;
  var.resize(points.rows());
  for (int i = 0; i < points.rows(); ++i) {
    var(i) = std::max(0.0, gp.hyper.signal_var - k.col(i).dot(kinv_k.col(i)) +
                               u.col(i).dot(gp.h_kinv_h_inv * u.col(i)));
  }
  if (gp.base) {
    Eigen::VectorXd base_mean, base_var;
    predict_many(*gp.base, points, base_mean, base_var);
    mean += base_mean;
    var += base_var;
  }
}

double predict_mean(const Gp& gp, std::span<const double> x) {
  const Eigen::Index n = gp.data.x.rows(), dims = gp.data.x.cols();
  double mean = gp.beta(0);
  for (int k = 1; k < gp.trend_terms; ++k) mean += gp.beta(k) * x[k - 1];
  for (Eigen::Index i = 0; i < n; ++i) {
    double r2 = 0.0;
    for (Eigen::Index d = 0; d < dims; ++d) {
      const double e = (x[d] - gp.data.x(i, d)) / gp.hyper.length(d);
      r2 += e * e;
    }
    const double s5r = std::sqrt(5.0 * r2);
    mean += gp.alpha(i) * gp.hyper.signal_var * (1.0 + s5r + (5.0 / 3.0) * r2) * std::exp(-s5r);
  }
  if (gp.base) mean += predict_mean(*gp.base, x);
  return mean;
}

Prediction predict(const Gp& gp, const Eigen::VectorXd& x) {
  Eigen::VectorXd mean, var;
  predict_many(gp, x.transpose(), mean, var);
  return {mean(0), var(0)};
}

}  // namespace rockcal::inference
