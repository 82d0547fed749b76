// Known functions and designs for the inference tests.
#pragma once

#include <cmath>
#include <random>

#include <Eigen/Dense>

namespace rockcal::inference::testing {

// ln of a degree-1 power law in two log strengths over the unit square (ln F from ln 10 to ln
// 1000): the calibration's loads in its emulators' coordinates, bent a little so that a linear
// trend does not carry all of it.
inline double ln_load(const Eigen::VectorXd& x, double a, double p, double q) {
  const double span = std::log(100.0);
  const double u = std::log(10.0) + span * x(0), v = std::log(10.0) + span * x(1);
  return a + p * u + q * v + 0.15 * std::sin(3.0 * x(0)) * std::cos(2.0 * x(1));
}

inline double ln_uct(const Eigen::VectorXd& x) {
  return ln_load(x, std::log(2500.0), 0.3, 0.7);
}
inline double ln_btt(const Eigen::VectorXd& x) {
  return ln_load(x, std::log(420.0), 0.8, 0.2);
}

// n points spread over the unit square (a seeded Latin hypercube).
inline Eigen::MatrixXd latin_square(int n, unsigned seed, int dims = 2) {
  std::mt19937 rng(seed);
  Eigen::MatrixXd x(n, dims);
  for (int k = 0; k < dims; ++k) {
    std::vector<int> perm(n);
    for (int i = 0; i < n; ++i) perm[i] = i;
    std::shuffle(perm.begin(), perm.end(), rng);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < n; ++i) x(i, k) = (perm[i] + u(rng)) / n;
  }
  return x;
}

}  // namespace rockcal::inference::testing
