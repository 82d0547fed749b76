// Template body of measure_interior (included by interior.hpp).
#pragma once

namespace rockcal {

template <class Region>
InteriorState measure_interior(const Simulation& sim, const std::vector<Vec3>& reference,
                               Region inside, double particle_volume_m3) {
  const Particles& p = sim.particles;
  std::vector<char> in(p.size(), 0);
  Vec3 mean_x = Vec3::Zero(), mean_u = Vec3::Zero();
  int n = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (!inside(reference[k])) continue;
    in[k] = 1;
    mean_x += reference[k];
    mean_u += p.pos[k] - reference[k];
    ++n;
  }
  InteriorState s{Mat3::Zero(), Mat3::Zero(), n};
  if (n < 4) return s;
  mean_x /= n;
  mean_u /= n;
  // Displacement gradient G minimising sum |u - mean_u - G (x - mean_x)|^2.
  Mat3 xx = Mat3::Zero(), ux = Mat3::Zero();
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (!in[k]) continue;
    const Vec3 dx = reference[k] - mean_x, du = (p.pos[k] - reference[k]) - mean_u;
    xx += dx * dx.transpose();
    ux += du * dx.transpose();
  }
  const Mat3 g = ux * xx.inverse();
  s.strain = 0.5 * (g + g.transpose());
  // Each bond contributes f_on_i (x) (x_j - x_i), shared half and half between its two particles.
  for (const Bond& b : sim.bonds) {
    const double share = 0.5 * (in[b.i] + in[b.j]);
    if (share == 0) continue;
    const BondLoad load = bond_load(b, p.pos[b.i], p.orient[b.i], p.pos[b.j], p.orient[b.j]);
    s.stress += share * load.force_i * (p.pos[b.j] - p.pos[b.i]).transpose();
  }
  s.stress /= n * particle_volume_m3;
  s.stress = 0.5 * (s.stress + s.stress.transpose()).eval();
  return s;
}

}  // namespace rockcal
