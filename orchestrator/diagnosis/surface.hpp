// Quadratic response surfaces: ln(observable) as a full quadratic polynomial of the unit-cube
// coordinates z (ln F_r0 and ln F_s0 mapped to [0, 1] over the bounds, plus the effect's s for a
// candidate), fitted by least squares to the grid runs. The polynomial is written in t = 2z - 1
// so that its columns are of order one and the least-squares system well conditioned.
#pragma once

#include <optional>
#include <span>
#include <vector>

// GCC 12 with -march=native (AVX-512) warns falsely about an uninitialised register inside
// Eigen's matrix-vector kernels (-Wmaybe-uninitialized in _mm512_extractf64x4_pd); the warning is
// in Eigen's code, not ours, so it is silenced for the Eigen headers only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Eigen/Dense>
#pragma GCC diagnostic pop

namespace rockcal::diagnosis {

struct Surface {
  int dims = 0;
  Eigen::VectorXd coef;  // 1, t_i, then t_i t_j for i <= j
  double rms = 0.0;      // rms of the fit's residuals at its points (ln units)
  int points = 0;
};

// 1 + d + d (d + 1) / 2.
int quadratic_term_count(int dims);
Eigen::VectorXd quadratic_terms(std::span<const double> z);

// Least squares through the points (z[k], y[k]); nullopt with fewer points than terms or a
// rank-deficient design (too many failed runs on one line of the grid).
std::optional<Surface> fit_surface(const std::vector<std::vector<double>>& z,
                                   const std::vector<double>& y);

double evaluate(const Surface& surface, std::span<const double> z);

}  // namespace rockcal::diagnosis
