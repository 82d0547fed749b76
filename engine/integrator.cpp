#include "engine/integrator.hpp"

#include <cmath>

namespace rockcal {

void kick(Particles& p, double h) {
  for (std::size_t k = 0; k < p.n_owned; ++k) {
    p.vel[k] += (h / p.mass[k]) * p.force[k];
    p.omega[k] += (h / p.inertia[k]) * p.torque[k];
  }
}

namespace {
// cos(a / 2) and sin(a / 2) / a from a^2, for a^2 < 1e-4: the series to the a^8 term, whose first
// omitted term is below 1e-21 there (a rounding of the result is 1e-16). A step turns a particle by
// far less than that (omega dt is of order 1e-6 in quasi-static runs), so libm's sincos, dear per
// particle per step, runs only for a fast spinner.
constexpr double kSeriesAngleSq = 1e-4;
inline void half_angle_series(double a2, double& c, double& s_over_a) {
  const double h2 = 0.25 * a2;
  c = 1.0 - h2 * (1.0 / 2 - h2 * (1.0 / 24 - h2 * (1.0 / 720 - h2 / 40320)));
  s_over_a = 0.5 * (1.0 - h2 * (1.0 / 6 - h2 * (1.0 / 120 - h2 * (1.0 / 5040 - h2 / 362880))));
}
}  // namespace

void drift(Particles& p, double dt) {
  for (std::size_t k = 0; k < p.n_owned; ++k) {
    p.pos[k] += dt * p.vel[k];
    // Spheres have isotropic inertia: omega is constant over the drift, so the rotation by
    // theta = omega dt, the unit quaternion (cos(a/2), sin(a/2) theta / a) with a = |theta|, is
    // exact.
    const Vec3 theta = dt * p.omega[k];
    const double a2 = theta.squaredNorm();
    double c, s_over_a;
    if (a2 < kSeriesAngleSq) {
      half_angle_series(a2, c, s_over_a);
    } else {
      const double a = std::sqrt(a2);
      c = std::cos(0.5 * a);
      s_over_a = std::sin(0.5 * a) / a;
    }
    const Vec3 u = s_over_a * theta;
    Quat& q = p.orient[k];
    const Vec3 v = q.vec();
    const double w = c * q.w() - u.dot(v);
    const Vec3 r = c * v + q.w() * u + u.cross(v);
    const double inv_norm = 1.0 / std::sqrt(w * w + r.squaredNorm());
    q.w() = w * inv_norm;
    q.vec() = inv_norm * r;
  }
}

namespace {
// Branch-free: velocity signs are unpredictable, and this runs six times per particle per step.
inline double sign(double x) {
  return static_cast<double>((x > 0) - (x < 0));
}

inline void damp(Vec3& f, const Vec3& v, double alpha) {
  for (int a = 0; a < 3; ++a) f[a] -= alpha * std::abs(f[a]) * sign(v[a]);
}
}  // namespace

void apply_damping(Particles& p, const Damping& d) {
  if (d.local > 0) {
    for (std::size_t k = 0; k < p.n_owned; ++k) {
      damp(p.force[k], p.vel[k], d.local);
      damp(p.torque[k], p.omega[k], d.local);
    }
  }
  if (d.viscous > 0) {
    for (std::size_t k = 0; k < p.n_owned; ++k) {
      p.force[k] -= d.viscous * p.mass[k] * p.vel[k];
      p.torque[k] -= d.viscous * p.inertia[k] * p.omega[k];
    }
  }
}

double kinetic_energy(const Particles& p) {
  double e = 0.0;
  for (std::size_t k = 0; k < p.n_owned; ++k)
    e += 0.5 * (p.mass[k] * p.vel[k].squaredNorm() + p.inertia[k] * p.omega[k].squaredNorm());
  return e;
}

}  // namespace rockcal
