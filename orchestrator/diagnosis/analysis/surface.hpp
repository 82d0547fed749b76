// Response surfaces: ln(observable) as a function of the unit-cube coordinates z (ln F_r0 and
// ln F_s0 mapped to [0, 1] over the bounds, plus the effect's s for a candidate), built from the
// grid runs. A global quadratic is too stiff for a box spanning a factor of 16 in each strength
// (its misfit at the grid points was as large as the effects it should resolve; docs/diagnosis.md),
// so the surface is a cubic radial basis function interpolant on top of a
// quadratic polynomial: s(z) = sum_k w_k |z - z_k|^3 + quadratic(z), with sum_k w_k q(z_k) = 0
// for every quadratic q. It reproduces quadratics exactly and passes through the runs; a
// smoothing term, chosen by leave-one-out cross-validation, lets it average over run-to-run
// scatter instead (at large smoothing it tends to the least-squares quadratic).
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
  Eigen::MatrixXd centres;  // one run's z per column
  Eigen::VectorXd weights;  // of |z - z_k|^3, per centre
  Eigen::VectorXd coef;     // quadratic part: 1, t_i, then t_i t_j for i <= j (t = 2z - 1)
  double smoothing = 0.0;   // added to the kernel matrix's diagonal; 0 = interpolation
  // Leave-one-out rms (ln units): each run predicted by the surface built without it. The error
  // to expect between the runs; NaN with too few runs to leave one out.
  double rms = 0.0;
  int points = 0;
};

// 1 + d + d (d + 1) / 2.
int quadratic_term_count(int dims);
Eigen::VectorXd quadratic_terms(std::span<const double> z);

// The surface through the points (z[k], y[k]); nullopt with fewer points than quadratic terms or
// points that do not determine a quadratic (too many failed runs on one line of the grid).
// `smoothing`: the kernel diagonal term; by default the one of a fixed ladder (0 to 1000) with the
// smallest leave-one-out rms.
std::optional<Surface> fit_surface(const std::vector<std::vector<double>>& z,
                                   const std::vector<double>& y,
                                   std::optional<double> smoothing = std::nullopt);

double evaluate(const Surface& surface, std::span<const double> z);

}  // namespace rockcal::diagnosis
