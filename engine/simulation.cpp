#include "engine/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include "engine/confinement.hpp"
#include "engine/units.hpp"

namespace rockcal {
namespace {

// Bond records for migration: ids, geometry, stiffness, strength and whether it is intact.
constexpr int kBondDoubles = 16;
// Contact history records: ids, tangential spring, rolling spring.
constexpr int kSpringDoubles = 8;

void pack_bond(const Bond& b, bool intact, std::vector<double>& out) {
  out.insert(out.end(), {double(b.id_i), double(b.id_j), b.r0, b.n0.x(), b.n0.y(), b.n0.z(), b.w_i,
                         b.kr, b.ks, b.kb, b.kt, b.fr0, b.fs0, b.gb0, b.gt0, intact ? 1.0 : 0.0});
}

Bond unpack_bond(const double* r, bool* intact) {
  Bond b{};
  b.id_i = static_cast<std::int64_t>(r[0]);
  b.id_j = static_cast<std::int64_t>(r[1]);
  b.r0 = r[2];
  b.n0 = Vec3(r[3], r[4], r[5]);
  b.w_i = r[6];
  b.kr = r[7];
  b.ks = r[8];
  b.kb = r[9];
  b.kt = r[10];
  set_strengths(b, r[11], r[12], r[13], r[14]);
  *intact = r[15] != 0.0;
  return b;
}

std::uint64_t key(std::int64_t a, std::int64_t b) {
  return (static_cast<std::uint64_t>(a) << 32) ^ static_cast<std::uint64_t>(b);
}

// Everything that leaves with migrating particles, in one buffer:
// [n_particles, n_bonds, n_springs, particle records..., bond records..., spring records...].
std::vector<double> pack_outbox(const Simulation& sim, const std::vector<std::int32_t>& leaving) {
  const Particles& p = sim.particles;
  std::unordered_set<std::int32_t> set(leaving.begin(), leaving.end());
  std::vector<double> parts, bonds, springs;
  for (std::int32_t k : leaving) pack_migrant(p, static_cast<std::size_t>(k), parts);
  std::size_t n_bonds = 0;
  auto add_bonds = [&](const std::vector<Bond>& list, bool intact) {
    for (const Bond& b : list)
      if (set.count(b.i) || set.count(b.j)) {
        pack_bond(b, intact, bonds);
        ++n_bonds;
      }
  };
  add_bonds(sim.bonds, true);
  add_bonds(sim.broken, false);
  std::vector<SpringRecord> history;
  for (std::int32_t k : leaving) sim.neighbours.history_of(p, k, history);
  for (const SpringRecord& s : history)
    springs.insert(springs.end(), {double(s.id_lo), double(s.id_hi), s.spring.x(), s.spring.y(),
                                   s.spring.z(), s.roll.x(), s.roll.y(), s.roll.z()});
  std::vector<double> out = {double(leaving.size()), double(n_bonds), double(history.size())};
  out.insert(out.end(), parts.begin(), parts.end());
  out.insert(out.end(), bonds.begin(), bonds.end());
  out.insert(out.end(), springs.begin(), springs.end());
  return out;
}

}  // namespace

void Simulation::initialise() {
  redistribute();
  compute_loads();
}

void Simulation::redistribute() {
  Particles& p = particles;
  std::vector<SpringRecord> incoming_springs;
  if (domain.parallel()) {
    // 1. Migration: owned particles that crossed a slab border move to the neighbour, with their
    //    bonds, contact history and platen springs.
    std::vector<std::int32_t> down, up;
    for (std::size_t k = 0; k < p.n_owned; ++k) {
      if (p.pos[k].z() < domain.z_lo)
        down.push_back(static_cast<std::int32_t>(k));
      else if (p.pos[k].z() >= domain.z_hi)
        up.push_back(static_cast<std::int32_t>(k));
    }
    const Received in = exchange(domain, pack_outbox(*this, down), pack_outbox(*this, up));

    // Keep the staying owned particles (in order), drop all ghosts.
    std::vector<char> leaves(p.n_owned, 0);
    for (std::int32_t k : down) leaves[k] = 1;
    for (std::int32_t k : up) leaves[k] = 1;
    std::size_t kept = 0;
    for (std::size_t k = 0; k < p.n_owned; ++k)
      if (!leaves[k]) p.copy(k, kept++);
    p.resize(kept);
    p.n_owned = kept;

    std::unordered_set<std::uint64_t> known;
    for (const Bond& b : bonds) known.insert(key(b.id_i, b.id_j));
    for (const Bond& b : broken) known.insert(key(b.id_i, b.id_j));
    for (const std::vector<double>* box : {&in.from_below, &in.from_above}) {
      if (box->empty()) continue;
      const double* r = box->data();
      const auto n_p = static_cast<std::size_t>(r[0]), n_b = static_cast<std::size_t>(r[1]),
                 n_s = static_cast<std::size_t>(r[2]);
      r += 3;
      for (std::size_t m = 0; m < n_p; ++m, r += kMigrantDoubles) unpack_migrant(r, p);
      for (std::size_t m = 0; m < n_b; ++m, r += kBondDoubles) {
        bool intact = false;
        const Bond b = unpack_bond(r, &intact);
        if (known.insert(key(b.id_i, b.id_j)).second) (intact ? bonds : broken).push_back(b);
      }
      for (std::size_t m = 0; m < n_s; ++m, r += kSpringDoubles)
        incoming_springs.push_back({static_cast<std::int64_t>(r[0]),
                                    static_cast<std::int64_t>(r[1]), Vec3(r[2], r[3], r[4]),
                                    Vec3(r[5], r[6], r[7])});
    }

    // 2. Ghosts: owned particles within the halo of a border are mirrored on that side.
    domain.send_below.clear();
    domain.send_above.clear();
    std::vector<double> to_below, to_above;
    for (std::size_t k = 0; k < p.n_owned; ++k) {
      const double z = p.pos[k].z();
      if (z < domain.z_lo + domain.halo) {
        domain.send_below.push_back(static_cast<std::int32_t>(k));
        pack_ghost(p, k, to_below);
      }
      if (z >= domain.z_hi - domain.halo) {
        domain.send_above.push_back(static_cast<std::int32_t>(k));
        pack_ghost(p, k, to_above);
      }
    }
    const Received ghosts = exchange(domain, to_below, to_above);
    domain.ghosts_from_below = ghosts.from_below.size() / kGhostDoubles;
    domain.ghosts_from_above = ghosts.from_above.size() / kGhostDoubles;
    for (std::size_t m = 0; m < domain.ghosts_from_below; ++m)
      unpack_ghost(&ghosts.from_below[m * kGhostDoubles], p);
    for (std::size_t m = 0; m < domain.ghosts_from_above; ++m)
      unpack_ghost(&ghosts.from_above[m * kGhostDoubles], p);

    // 3. Local indices of the bonds from their ids; bonds without an owned particle belong
    // elsewhere.
    std::unordered_map<std::int64_t, std::int32_t> local;
    local.reserve(p.size());
    for (std::size_t k = 0; k < p.size(); ++k) local.emplace(p.id[k], static_cast<std::int32_t>(k));
    auto reindex = [&](std::vector<Bond>& list, bool intact) {
      std::size_t out = 0;
      for (std::size_t m = 0; m < list.size(); ++m) {
        Bond b = list[m];
        auto a = local.find(b.id_i), c = local.find(b.id_j);
        const bool a_owned = a != local.end() && static_cast<std::size_t>(a->second) < p.n_owned;
        const bool c_owned = c != local.end() && static_cast<std::size_t>(c->second) < p.n_owned;
        if (!a_owned && !c_owned) continue;
        if (a == local.end() || c == local.end()) {
          if (!intact)
            continue;  // a broken bond's far end is out of reach: it cannot be touched either
          throw std::runtime_error("a bond reaches beyond the ghost layer; the halo is too thin");
        }
        b.i = a->second;
        b.j = c->second;
        list[out++] = b;
      }
      list.resize(out);
    };
    reindex(bonds, true);
    reindex(broken, false);
  }
  neighbours.build(p, bonds, broken, incoming_springs);
}

void Simulation::compute_loads() {
  particles.clear_loads();
  const std::size_t broken_before = broken.size(), events_before = breaks.size();
  accumulate_bond_forces(bonds, particles, break_rule, step, broken, breaks);
  for (std::size_t k = broken_before; k < broken.size(); ++k)
    neighbours.mark_broken(broken[k].i, broken[k].j);
  accumulate_contact_forces(neighbours, particles, contact, dt);
  for (Wall& w : walls) accumulate_wall_forces(w, particles, dt);
  if (confining_force_n != 0.0) accumulate_confining_forces(particles, confining_force_n);
  apply_damping(particles, damping);

  // The figures every rank needs to take the same decisions: platen reactions, breaks, stop.
  double global[3 * kMaxWalls + 2] = {};
  for (std::size_t w = 0; w < walls.size(); ++w)
    for (int a = 0; a < 3; ++a) global[3 * w + a] = walls[w].reaction[a];
  global[3 * kMaxWalls] = static_cast<double>(breaks.size() - events_before);
  global[3 * kMaxWalls + 1] = stop_local ? 1.0 : 0.0;
  if (domain.parallel()) {
    reduce_sum(domain, global, 3 * kMaxWalls + 1);
    reduce_max(domain, &global[3 * kMaxWalls + 1], 1);
  }
  for (std::size_t w = 0; w < walls.size(); ++w)
    walls[w].reaction = Vec3(global[3 * w], global[3 * w + 1], global[3 * w + 2]);
  broken_total += static_cast<std::int64_t>(global[3 * kMaxWalls]);
  stop_global = global[3 * kMaxWalls + 1] > 0.0;
}

void Simulation::advance() {
  kick(particles, 0.5 * dt);
  drift(particles, dt);
  for (Wall& w : walls) w.point += dt * w.velocity;
  ++step;
  time += dt;
  double rebuild = neighbours.needs_rebuild(particles) ? 1.0 : 0.0;
  reduce_max(domain, &rebuild, 1);
  if (rebuild > 0)
    redistribute();
  else
    refresh_ghosts(domain, particles);
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
  // Unbonded contacts may form anywhere: no particle is allowed below a contact's stiffness.
  const double contact_k = sim.contact.kn_n_m + sim.contact.ks_n_m;
  const double contact_k_rot_per_r2 = sim.contact.ks_n_m + rolling_stiffness_per_r2(sim.contact);
  double dt = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < p.n_owned; ++k) {
    const double lever = p.radius[k];
    const double kt = std::max(k_trans[k], contact_k) + wall_k;
    const double kr =
        std::max(k_rot[k], contact_k_rot_per_r2 * lever * lever) + wall_k * lever * lever;
    dt = std::min(dt, critical_time_step(p.mass[k], p.inertia[k], kt, kr));
  }
  reduce_min(sim.domain, &dt, 1);
  return safety * dt;
}

}  // namespace rockcal
