#include "orchestrator/diagnosis/surface.hpp"

#include <cmath>

namespace rockcal::diagnosis {

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
                                   const std::vector<double>& y) {
  if (z.empty() || z.size() != y.size()) return std::nullopt;
  const int dims = int(z[0].size());
  const int terms = quadratic_term_count(dims);
  const int n = int(z.size());
  if (n < terms) return std::nullopt;
  Eigen::MatrixXd a(n, terms);
  Eigen::VectorXd b(n);
  for (int k = 0; k < n; ++k) {
    a.row(k) = quadratic_terms(z[k]).transpose();
    b[k] = y[k];
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  if (qr.rank() < terms) return std::nullopt;
  Surface s;
  s.dims = dims;
  s.coef = qr.solve(b);
  s.points = n;
  s.rms = std::sqrt((a * s.coef - b).squaredNorm() / n);
  return s;
}

double evaluate(const Surface& surface, std::span<const double> z) {
  return quadratic_terms(z).dot(surface.coef);
}

}  // namespace rockcal::diagnosis
