#include "engine/integrator.hpp"

#include <cmath>

namespace rockcal {

void kick(Particles& p, double h) {
  for (std::size_t k = 0; k < p.n_owned; ++k) {
    p.vel[k] += (h / p.mass[k]) * p.force[k];
    p.omega[k] += (h / p.inertia[k]) * p.torque[k];
  }
}

void drift(Particles& p, double dt) {
  for (std::size_t k = 0; k < p.n_owned; ++k) {
    p.pos[k] += dt * p.vel[k];
    // Spheres have isotropic inertia: omega is constant over the drift, so this rotation is exact.
    p.orient[k] = (rotation_from_vector(dt * p.omega[k]) * p.orient[k]).normalized();
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
