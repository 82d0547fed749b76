// Template bodies of interior_strain and measure_interior (included by interior.hpp).
#pragma once

namespace rockcal {

template <class Region>
InteriorState interior_strain(const Simulation& sim,
                              const std::unordered_map<std::int64_t, Vec3>& reference,
                              Region inside, InteriorScratch& scratch) {
  const Particles& p = sim.particles;
  std::vector<char>& in = scratch.in;
  std::vector<Vec3>& ref = scratch.ref;
  in.assign(p.size(), 0);
  ref.resize(p.n_owned);
  // sums[0..2] x, sums[3..5] u, sums[6] count
  double sums[7] = {};
  for (std::size_t k = 0; k < p.n_owned; ++k) {
    auto it = reference.find(p.id[k]);
    if (it == reference.end() || !inside(it->second)) continue;
    in[k] = 1;
    ref[k] = it->second;
    const Vec3 u = p.pos[k] - ref[k];
    for (int a = 0; a < 3; ++a) {
      sums[a] += ref[k][a];
      sums[3 + a] += u[a];
    }
    sums[6] += 1.0;
  }
  reduce_sum(sim.domain, sums, 7);
  const int n = static_cast<int>(sums[6]);
  InteriorState s{Mat3::Zero(), Mat3::Zero(), n};
  if (n < 4) return s;
  const Vec3 mean_x = Vec3(sums[0], sums[1], sums[2]) / n,
             mean_u = Vec3(sums[3], sums[4], sums[5]) / n;

  // Displacement gradient G minimising sum |u - mean_u - G (x - mean_x)|^2.
  Mat3 mats[2] = {Mat3::Zero(), Mat3::Zero()};  // xx, ux
  for (std::size_t k = 0; k < p.n_owned; ++k) {
    if (!in[k]) continue;
    const Vec3 dx = ref[k] - mean_x, du = (p.pos[k] - ref[k]) - mean_u;
    mats[0] += dx * dx.transpose();
    mats[1] += du * dx.transpose();
  }
  reduce_sum(sim.domain, mats[0].data(), 18);  // two contiguous 3x3 matrices
  const Mat3 g = mats[1] * mats[0].inverse();
  s.strain = 0.5 * (g + g.transpose());
  return s;
}

template <class Region>
InteriorState measure_interior(const Simulation& sim,
                               const std::unordered_map<std::int64_t, Vec3>& reference,
                               Region inside, double particle_volume_m3, InteriorScratch& scratch) {
  InteriorState s = interior_strain(sim, reference, inside, scratch);
  if (s.particles < 4) return s;
  // The stress: every bond adds f_on_i (x) (x_j - x_i) (the same from either end), half for each
  // end in the region.
  const Particles& p = sim.particles;
  const std::vector<char>& in = scratch.in;
  Mat3 stress = Mat3::Zero();
  for (const Bond& b : sim.bonds) {
    const double share = 0.5 * ((static_cast<std::size_t>(b.i) < p.n_owned && in[b.i]) +
                                (static_cast<std::size_t>(b.j) < p.n_owned && in[b.j]));
    if (share == 0) continue;
    const BondLoad load = bond_load(b, p.pos[b.i], p.orient[b.i], p.pos[b.j], p.orient[b.j]);
    stress += share * load.force_i * (p.pos[b.j] - p.pos[b.i]).transpose();
  }
  reduce_sum(sim.domain, stress.data(), 9);
  s.stress = stress / (s.particles * particle_volume_m3);
  s.stress = (0.5 * (s.stress + s.stress.transpose())).eval();
  return s;
}

}  // namespace rockcal
