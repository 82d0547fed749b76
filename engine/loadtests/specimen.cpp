#include "engine/loadtests/specimen.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "engine/effects/effect.hpp"
#include "engine/loadtests/brazilian.hpp"
#include "engine/packing/cache.hpp"
#include "engine/packing/fcc.hpp"
#include "engine/packing/floaters.hpp"
#include "engine/stop_request.hpp"
#include "engine/units.hpp"

namespace rockcal {

// Bonds join particles that touch. In a lattice the tolerance only absorbs round-off; a jammed
// random packing leaves small gaps between neighbours, bridged up to 5% of the pair's mean radius.
constexpr double kLatticeBondTolerance = 1e-6;
constexpr double kRandomBondTolerance = 0.025;

namespace {

double bond_tolerance(const JobSpec& spec) {
  const double touching =
      spec.sample.packing == "random" ? kRandomBondTolerance : kLatticeBondTolerance;
  return std::max(touching, spec.bond.reach - 1.0);
}

// The particles of the specimen before bonding, floaters removed.
std::vector<Sphere> specimen_spheres(const JobSpec& spec, std::int64_t* floaters) {
  const double r = spec.sample.radius_m;
  const bool btt = spec.test == TestKind::btt;
  const Disc disc = btt_disc(spec);
  const Cylinder cylinder{spec.sample.diameter_m, spec.sample.height_m};
  std::vector<Sphere> out;
  if (spec.sample.packing == "random") {
    const RandomPackingParams params{r, spec.sample.radius_ratio, spec.sample.seed};
    const auto dir = default_packing_cache_dir();
    // A flattened disc is packed against walls on its flats, so its loaded faces are flat.
    out = btt ? cached_random_dense(disc, params, dir) : cached_random_dense(cylinder, params, dir);
  } else {
    const LatticePlacement place =
        spec.sample.lattice == "aligned" ? aligned_lattice() : seeded_lattice(spec.sample.seed, r);
    const std::vector<Vec3> centres =
        btt ? fcc_centres(disc, r, place) : fcc_centres(cylinder, r, place);
    for (const Vec3& c : centres) out.push_back({c, r});
  }
  *floaters = static_cast<std::int64_t>(remove_floaters(out, bond_tolerance(spec)));
  return out;
}

// The loading surfaces, touching the outermost particles along z: flat platens, or (BTT, curved
// jaws) concave jaws placed so that no particle overlaps them at the start.
void add_loading_walls(Simulation& sim, const JobSpec& spec, const std::vector<Sphere>& spheres,
                       const BondStiffness& k) {
  const double mu = spec.loading.platen_friction;
  if (spec.test == TestKind::btt && spec.loading.btt_geometry == BttGeometry::curved_jaws) {
    const double rj = spec.loading.jaw_radius_ratio * 0.5 * spec.sample.diameter_m;
    double axis_lo = std::numeric_limits<double>::infinity(), axis_hi = -axis_lo;
    for (const Sphere& s : spheres) {
      const double reach = rj - s.radius, x = s.centre.x();
      if (std::abs(x) >= reach) continue;
      const double h = std::sqrt(reach * reach - x * x);
      axis_lo = std::min(axis_lo, s.centre.z() + h);  // bottom jaw: axis above the particles
      axis_hi = std::max(axis_hi, s.centre.z() - h);
    }
    sim.walls.push_back(make_jaw(Vec3(0, 0, 1), Vec3(0, 0, axis_lo - rj), Vec3::UnitY(), rj,
                                 kJawHalfAngleRad, k.kr_n_m, k.ks_n_m, mu, kBottomPlaten));
    sim.walls.push_back(make_jaw(Vec3(0, 0, -1), Vec3(0, 0, axis_hi + rj), Vec3::UnitY(), rj,
                                 kJawHalfAngleRad, k.kr_n_m, k.ks_n_m, mu, kTopPlaten));
    return;
  }
  double z_lo = spheres[0].centre.z() - spheres[0].radius,
         z_hi = spheres[0].centre.z() + spheres[0].radius;
  for (const Sphere& s : spheres) {
    z_lo = std::min(z_lo, s.centre.z() - s.radius);
    z_hi = std::max(z_hi, s.centre.z() + s.radius);
  }
  sim.walls.push_back(
      make_wall(Vec3(0, 0, 1), Vec3(0, 0, z_lo), k.kr_n_m, k.ks_n_m, mu, kBottomPlaten));
  sim.walls.push_back(
      make_wall(Vec3(0, 0, -1), Vec3(0, 0, z_hi), k.kr_n_m, k.ks_n_m, mu, kTopPlaten));
}

}  // namespace
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
  r.floaters_removed = sim.floaters_removed;
}

namespace {

// Ghosts must cover the contact reach (2R + skin) and the longest a bond gets before it breaks.
// `longest_bond`: the longest rest length a bond may have (2 r_max for touching neighbours).
double halo_for(double r_max, double longest_bond, double skin, double longest_stretch) {
  return std::max(2.0 * r_max, longest_bond) + skin + std::max(0.5 * r_max, longest_stretch);
}

// Effects may have made some bonds stronger than the job's F_r0 (heterogeneity), so that they
// stretch farther before breaking: widens the ghost layer to match (all ranks alike).
void widen_halo_for_bonds(Simulation& sim, double r_max) {
  Domain& d = sim.domain;
  if (!d.parallel()) return;
  double reach[2] = {0.0, 0.0};  // longest stretch, longest bond
  for (const Bond& b : sim.bonds) {
    reach[0] = std::max(reach[0], 2.0 * b.fr0 / b.kr);
    reach[1] = std::max(reach[1], b.r0);
  }
  reduce_max(d, reach, 2);
  const double halo = halo_for(r_max, reach[1], sim.neighbours.skin, reach[0]);
  if (halo <= d.halo) return;
  double too_thin = std::isfinite(d.z_lo) && std::isfinite(d.z_hi) && d.z_hi - d.z_lo < halo;
  reduce_max(d, &too_thin, 1);
  if (too_thin > 0)
    throw std::runtime_error("too many ranks for this specimen: a slab is thinner than the halo " +
                             std::to_string(halo) + " m its strongest bonds need");
  d.halo = halo;
  sim.redistribute();
}

}  // namespace

Simulation make_specimen(const JobSpec& job, MPI_Comm comm) {
  const SetupStage stage;  // a stop now ends the process at once (engine/stop_request.hpp)
  const JobSpec spec = effective_spec(job);  // a no-op when the driver already made it effective
  std::int64_t floaters = 0;
  const std::vector<Sphere> spheres = specimen_spheres(spec, &floaters);
  if (spheres.empty())
    throw std::runtime_error("the specimen holds no particle (" + std::to_string(floaters) +
                             " removed with fewer than " + std::to_string(kMinBondsToHold) +
                             " bonds): it is too small for its particles");
  const double r = spec.sample.radius_m;
  double r_max = 0.0;
  for (const Sphere& s : spheres) r_max = std::max(r_max, s.radius);
  const BondStiffness k = bond_stiffness(spec, r);

  Simulation sim;
  sim.neighbours.skin = kSkinRadii * r;
  int ranks = 1;
  if (comm != MPI_COMM_NULL) MPI_Comm_size(comm, &ranks);
  if (ranks > 1) {
    std::vector<double> z(spheres.size());
    std::transform(spheres.begin(), spheres.end(), z.begin(),
                   [](const Sphere& s) { return s.centre.z(); });
    sim.domain = make_domain(comm, std::move(z),
                             halo_for(r_max, 2.0 * r_max * (1.0 + bond_tolerance(spec)),
                                      sim.neighbours.skin, 2.0 * spec.bond.fr0_n / k.kr_n_m));
  }

  // This rank's slab plus its halo, with global ids; bonds are found among them.
  const Domain& d = sim.domain;
  auto add = [&](Particles& p, const Vec3& x, double radius, std::int64_t id) {
    const double m = sphere_mass(spec.material.density_kg_m3, radius);
    p.add(x, radius, m, sphere_inertia(m, radius), id);
  };
  Particles near;
  for (std::size_t c = 0; c < spheres.size(); ++c) {
    const double z = spheres[c].centre.z();
    if (z >= d.z_lo - d.halo && z < d.z_hi + d.halo)
      add(near, spheres[c].centre, spheres[c].radius, std::int64_t(c));
  }
  sim.bonds = bond_neighbours(
      near, bond_tolerance(spec), [&](double radius) { return bond_stiffness(spec, radius); },
      spec.bond.fr0_n, spec.bond.fs0_n);
  for (std::size_t c = 0; c < near.size(); ++c) {
    const double z = near.pos[c].z();
    if (z >= d.z_lo && z < d.z_hi) add(sim.particles, near.pos[c], near.radius[c], near.id[c]);
  }
  // In serial every particle is owned, in the order of `near`: the bond indices hold as they are.
  // In parallel redistribute() re-indexes the bonds by id.
  sim.floaters_removed = floaters;

  sim.contact = ContactLaw{k.kr_n_m, k.ks_n_m, spec.contact.friction, spec.contact.friction};
  sim.damping = Damping{spec.damping.local, spec.damping.viscous};

  add_loading_walls(sim, spec, spheres, k);

  sim.redistribute();  // ghosts and local bond indices, which the time step estimate needs
  apply_specimen_effects(sim, spec);
  widen_halo_for_bonds(sim, r_max);
  sim.dt = spec.loading.dt_s ? *spec.loading.dt_s : auto_time_step(sim, spec.loading.dt_safety);
  sim.compute_loads();
  return sim;
}

}  // namespace rockcal
