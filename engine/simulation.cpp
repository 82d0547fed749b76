#include "engine/simulation.hpp"

#include <algorithm>
#include <cmath>

#include "engine/units.hpp"

namespace rockcal {

void Simulation::initialise() {
  neighbours.build(particles, bonds, broken);
  compute_loads();
}

void Simulation::compute_loads() {
  particles.clear_loads();
  const std::size_t first_new = breaks.size();
  accumulate_bond_forces(bonds, particles, break_rule, step, broken, breaks);
  for (std::size_t k = broken.size() - (breaks.size() - first_new); k < broken.size(); ++k)
    neighbours.mark_broken(broken[k].i, broken[k].j);
  accumulate_contact_forces(neighbours, particles, contact, dt);
  for (Wall& w : walls) accumulate_wall_forces(w, particles, dt);
  apply_damping(particles, damping);
}

void Simulation::advance() {
  kick(particles, 0.5 * dt);
  drift(particles, dt);
  for (Wall& w : walls) w.point += dt * w.velocity;
  ++step;
  time += dt;
  if (neighbours.needs_rebuild(particles)) neighbours.build(particles, bonds, broken);
  compute_loads();
  kick(particles, 0.5 * dt);
}

double auto_time_step(const Simulation& sim, double safety) {
  const Particles& p = sim.particles;
  std::vector<double> k_trans(p.size(), 0.0), k_rot(p.size(), 0.0);
  for (const Bond& b : sim.bonds) {
    const double kt = b.kr + b.ks;
    const double li = b.w_i * b.r0, lj = (1.0 - b.w_i) * b.r0;  // shear levers
    k_trans[b.i] += kt;
    k_trans[b.j] += kt;
    k_rot[b.i] += b.ks * li * li + b.kb + b.kt;
    k_rot[b.j] += b.ks * lj * lj + b.kb + b.kt;
  }
  double wall_k = 0.0;
  for (const Wall& w : sim.walls) wall_k = std::max(wall_k, w.kn_n_m + w.ks_n_m);
  // Unbonded contacts may form anywhere: no particle is allowed below a platen's stiffness.
  const double contact_k = sim.contact.kn_n_m + sim.contact.ks_n_m;
  double dt = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < p.size(); ++k) {
    const double lever = p.radius[k];
    const double kt = std::max(k_trans[k], contact_k) + wall_k;
    const double kr =
        std::max(k_rot[k], sim.contact.ks_n_m * lever * lever) + wall_k * lever * lever;
    dt = std::min(dt, critical_time_step(p.mass[k], p.inertia[k], kt, kr));
  }
  return safety * dt;
}

}  // namespace rockcal
