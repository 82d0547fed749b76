#include "engine/loadtests/specimen.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/packing/fcc.hpp"
#include "engine/units.hpp"

namespace rockcal {

// Bonds join particles that touch; the tolerance only absorbs round-off of the lattice coordinates.
constexpr double kBondTolerance = 1e-6;
constexpr double kSkinRadii = 0.3;  // neighbour-list skin, in particle radii

double loaded_length(const JobSpec& spec) {
  return spec.test == TestKind::btt ? spec.sample.diameter_m : spec.sample.height_m;
}

double particle_volume(const JobSpec& spec) {
  const double r = spec.sample.radius_m;
  const double fcc_solid_fraction = M_PI / (3.0 * std::sqrt(2.0));
  return (4.0 / 3.0 * M_PI * r * r * r) / fcc_solid_fraction;
}

double wave_transit_time(const JobSpec& spec) {
  const double r = spec.sample.radius_m;
  // Eq. 3 inverted: the lattice's E = 2 (1 - 2 nu) K_r / (sqrt(2) R).
  const double kr = bond_stiffness(spec, r).kr_n_m;
  const double e_lattice = 2.0 * (1.0 - 2.0 * spec.material.nu) * kr / (std::sqrt(2.0) * r);
  const double rho_bulk = sphere_mass(spec.material.density_kg_m3, r) / particle_volume(spec);
  return loaded_length(spec) / std::sqrt(e_lattice / rho_bulk);
}

void count_specimen(const Simulation& sim, TestResult& r) {
  double counts[2] = {static_cast<double>(sim.particles.n_owned), 0.0};
  for (const Bond& b : sim.bonds)
    counts[1] += static_cast<std::size_t>(b.i) < sim.particles.n_owned ? 1.0 : 0.0;
  reduce_sum(sim.domain, counts, 2);
  r.particles = static_cast<std::int64_t>(counts[0]);
  r.bonds = static_cast<std::int64_t>(counts[1]);
}

Simulation make_specimen(const JobSpec& spec, MPI_Comm comm) {
  const double r = spec.sample.radius_m;
  std::vector<Vec3> centres;
  if (spec.test == TestKind::btt) {
    centres = fcc_centres(Disc{spec.sample.diameter_m, spec.sample.btt_thickness()}, r);
  } else {
    centres = fcc_centres(Cylinder{spec.sample.diameter_m, spec.sample.height_m}, r);
  }
  if (centres.empty()) throw std::runtime_error("the specimen holds no particle");
  const BondStiffness k = bond_stiffness(spec, r);

  Simulation sim;
  sim.neighbours.skin = kSkinRadii * r;
  int ranks = 1;
  if (comm != MPI_COMM_NULL) MPI_Comm_size(comm, &ranks);
  if (ranks > 1) {
    // Ghosts must cover the contact reach (2R + skin) and the longest a bond gets before it breaks.
    const double stretch = std::max(0.5 * r, 2.0 * spec.bond.fr0_n / k.kr_n_m);
    std::vector<double> z(centres.size());
    std::transform(centres.begin(), centres.end(), z.begin(), [](const Vec3& c) { return c.z(); });
    sim.domain = make_domain(comm, std::move(z), 2.0 * r + sim.neighbours.skin + stretch);
  }

  // This rank's slab plus its halo, with global ids; bonds are found among them.
  const Domain& d = sim.domain;
  const double m = sphere_mass(spec.material.density_kg_m3, r);
  Particles near;
  for (std::size_t c = 0; c < centres.size(); ++c) {
    const double z = centres[c].z();
    if (z >= d.z_lo - d.halo && z < d.z_hi + d.halo)
      near.add(centres[c], r, m, sphere_inertia(m, r), static_cast<std::int64_t>(c));
  }
  sim.bonds = bond_neighbours(
      near, kBondTolerance, [&](double radius) { return bond_stiffness(spec, radius); },
      spec.bond.fr0_n, spec.bond.fs0_n);
  for (std::size_t c = 0; c < near.size(); ++c) {
    const double z = near.pos[c].z();
    if (z >= d.z_lo && z < d.z_hi)
      sim.particles.add(near.pos[c], r, m, sphere_inertia(m, r), near.id[c]);
  }
  if (!d.parallel()) sim.particles = std::move(near);  // same set, same order as the bonds' indices

  sim.contact = ContactLaw{k.kr_n_m, k.ks_n_m, spec.contact.friction, spec.contact.friction};
  sim.damping = Damping{spec.damping.local, spec.damping.viscous};

  double z_lo = centres[0].z(), z_hi = centres[0].z();
  for (const Vec3& c : centres) {
    z_lo = std::min(z_lo, c.z());
    z_hi = std::max(z_hi, c.z());
  }
  const double mu = spec.loading.platen_friction;
  sim.walls.push_back(
      make_wall(Vec3(0, 0, 1), Vec3(0, 0, z_lo - r), k.kr_n_m, k.ks_n_m, mu, kBottomPlaten));
  sim.walls.push_back(
      make_wall(Vec3(0, 0, -1), Vec3(0, 0, z_hi + r), k.kr_n_m, k.ks_n_m, mu, kTopPlaten));

  sim.redistribute();  // ghosts and local bond indices, which the time step estimate needs
  sim.dt = spec.loading.dt_s ? *spec.loading.dt_s : auto_time_step(sim, spec.loading.dt_safety);
  sim.compute_loads();
  return sim;
}

}  // namespace rockcal
