#include "engine/loadtests/specimen.hpp"

#include <stdexcept>

#include "engine/packing/fcc.hpp"
#include "engine/units.hpp"

namespace rockcal {

// Bonds join particles that touch; the tolerance only absorbs round-off of the lattice coordinates.
constexpr double kBondTolerance = 1e-6;

double loaded_length(const JobSpec& spec) {
  return spec.test == TestKind::btt ? spec.sample.diameter_m : spec.sample.height_m;
}

Simulation make_specimen(const JobSpec& spec) {
  const double r = spec.sample.radius_m;
  std::vector<Vec3> centres;
  if (spec.test == TestKind::btt) {
    centres = fcc_centres(Disc{spec.sample.diameter_m, spec.sample.btt_thickness()}, r);
  } else {
    centres = fcc_centres(Cylinder{spec.sample.diameter_m, spec.sample.height_m}, r);
  }
  if (centres.empty()) throw std::runtime_error("the specimen holds no particle");

  Simulation sim;
  const double m = sphere_mass(spec.material.density_kg_m3, r);
  for (std::size_t k = 0; k < centres.size(); ++k)
    sim.particles.add(centres[k], r, m, sphere_inertia(m, r), static_cast<std::int64_t>(k));

  sim.bonds = bond_neighbours(
      sim.particles, kBondTolerance, [&](double radius) { return bond_stiffness(spec, radius); },
      spec.bond.fr0_n, spec.bond.fs0_n);

  const BondStiffness k = bond_stiffness(spec, r);
  sim.contact = ContactLaw{k.kr_n_m, k.ks_n_m, spec.contact.friction, spec.contact.friction};
  sim.damping = Damping{spec.damping.local, spec.damping.viscous};
  sim.neighbours.skin = 0.3 * r;

  double z_lo = centres[0].z(), z_hi = centres[0].z();
  for (const Vec3& c : centres) {
    z_lo = std::min(z_lo, c.z());
    z_hi = std::max(z_hi, c.z());
  }
  const std::size_t n = sim.particles.size();
  const double mu = spec.loading.platen_friction;
  sim.walls.push_back(make_wall(Vec3(0, 0, 1), Vec3(0, 0, z_lo - r), k.kr_n_m, k.ks_n_m, mu, n));
  sim.walls.push_back(make_wall(Vec3(0, 0, -1), Vec3(0, 0, z_hi + r), k.kr_n_m, k.ks_n_m, mu, n));

  sim.dt = spec.loading.dt_s ? *spec.loading.dt_s : auto_time_step(sim, spec.loading.dt_safety);
  sim.initialise();
  return sim;
}

}  // namespace rockcal
