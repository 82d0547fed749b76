#include "orchestrator/diagnosis/analysis/surface.hpp"

#include <cmath>
#include <iterator>
#include <limits>

namespace rockcal::diagnosis {
namespace {

// Smoothing values tried, relative to the kernel's scale (|z - z_k|^3 is of order 1 on the unit
// cube). 0 interpolates; the largest leaves the kernel part little weight, so the surface is then
// close to the least-squares quadratic.
constexpr double kSmoothing[] = {0.0, 1e-4, 1e-3, 1e-2, 1e-1, 1.0, 10.0, 1000.0};

double kernel(double r) {
  return r * r * r;
}

struct Solved {
  Eigen::VectorXd weights, coef;
  double loo_rms = std::numeric_limits<double>::quiet_NaN();
};

// The saddle-point system [[K + aI, P], [P^T, 0]] [w; c] = [y; 0]. Leave-one-out residuals from
// one factorisation: y_k - s_{-k}(z_k) = w_k / (M^-1)_kk (Rippa 1999; with the smoothing term
// this is the kriging-with-nugget identity).
std::optional<Solved> solve(const Eigen::MatrixXd& k, const Eigen::MatrixXd& p,
                            const Eigen::VectorXd& y, double smoothing) {
  const int n = int(k.rows()), m = int(p.cols());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n + m, n + m);
  a.topLeftCorner(n, n) = k + smoothing * Eigen::MatrixXd::Identity(n, n);
  a.topRightCorner(n, m) = p;
  a.bottomLeftCorner(m, n) = p.transpose();
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(a);
  if (!lu.isInvertible()) return std::nullopt;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + m);
  rhs.head(n) = y;
  const Eigen::VectorXd x = lu.solve(rhs);
  if (!x.allFinite()) return std::nullopt;
  Solved s{x.head(n), x.tail(m)};
  if (n > m) {  // with n = m the quadratic alone takes every point: nothing to leave out
    const Eigen::MatrixXd inv = lu.inverse();
    double sum = 0.0;
    int i = 0;
    for (; i < n && std::abs(inv(i, i)) > 1e-14; ++i) sum += std::pow(x[i] / inv(i, i), 2);
    if (i == n) s.loo_rms = std::sqrt(sum / n);  // else a point the others cannot predict
  }
  return s;
}

}  // namespace

int quadratic_term_count(int dims) {
  return 1 + dims + dims * (dims + 1) / 2;
}

Eigen::VectorXd quadratic_terms(std::span<const double> z) {
  const int d = int(z.size());
  Eigen::VectorXd terms(quadratic_term_count(d));
  int k = 0;
  terms[k++] = 1.0;
  for (int i = 0; i < d; ++i) terms[k++] = 2.0 * z[i] - 1.0;
  for (int i = 0; i < d; ++i) {
    for (int j = i; j < d; ++j) terms[k++] = (2.0 * z[i] - 1.0) * (2.0 * z[j] - 1.0);
  }
  return terms;
}

std::optional<Surface> fit_surface(const std::vector<std::vector<double>>& z,
                                   const std::vector<double>& y, std::optional<double> smoothing) {
  if (z.empty() || z.size() != y.size()) return std::nullopt;
  const int dims = int(z[0].size());
  const int terms = quadratic_term_count(dims);
  const int n = int(z.size());
  if (n < terms) return std::nullopt;
  Eigen::MatrixXd centres(dims, n), p(n, terms), k(n, n);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < dims; ++d) centres(d, i) = z[i][d];
    p.row(i) = quadratic_terms(z[i]).transpose();
    b[i] = y[i];
  }
  // The points must determine a quadratic, or the interpolant is not unique.
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(p);
  if (qr.rank() < terms) return std::nullopt;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) k(i, j) = kernel((centres.col(i) - centres.col(j)).norm());

  std::optional<Solved> best;
  double best_smoothing = 0.0;
  const std::vector<double> ladder =
      smoothing ? std::vector<double>{*smoothing}
                : std::vector<double>(std::begin(kSmoothing), std::end(kSmoothing));
  for (double a : ladder) {
    std::optional<Solved> s = solve(k, p, b, a);
    if (!s) continue;
    // Ties and an unavailable leave-one-out keep the smaller smoothing (the first tried).
    if (!best || (std::isfinite(s->loo_rms) &&
                  !(std::isfinite(best->loo_rms) && s->loo_rms >= best->loo_rms))) {
      best = std::move(s);
      best_smoothing = a;
    }
  }
  if (!best) return std::nullopt;
  Surface s;
  s.dims = dims;
  s.centres = std::move(centres);
  s.weights = std::move(best->weights);
  s.coef = std::move(best->coef);
  s.smoothing = best_smoothing;
  s.rms = best->loo_rms;
  s.points = n;
  return s;
}

double evaluate(const Surface& surface, std::span<const double> z) {
  double v = quadratic_terms(z).dot(surface.coef);
  const int n = int(surface.weights.size());
  for (int i = 0; i < n; ++i) {
    double r2 = 0.0;
    for (int d = 0; d < surface.dims; ++d) {
      const double e = z[d] - surface.centres(d, i);
      r2 += e * e;
    }
    v += surface.weights[i] * kernel(std::sqrt(r2));
  }
  return v;
}

}  // namespace rockcal::diagnosis
