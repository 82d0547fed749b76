// Template body of bond_neighbours (included by simulation.hpp).
#pragma once

namespace rockcal {

template <class StiffnessFn>
std::vector<Bond> bond_neighbours(const Particles& p, double tolerance,
                                  StiffnessFn stiffness_for_radius, double fr0, double fs0) {
  NeighbourList finder;
  double r_max = 0.0;
  for (double r : p.radius) r_max = std::max(r_max, r);
  finder.skin = 2.0 * tolerance * r_max;
  finder.build(p, {}, {});
  std::vector<Bond> bonds;
  for (const ContactPair& c : finder.pairs) {
    const double reach = (p.radius[c.i] + p.radius[c.j]) * (1.0 + tolerance);
    if ((p.pos[c.j] - p.pos[c.i]).squaredNorm() > reach * reach) continue;
    const auto k = stiffness_for_radius(0.5 * (p.radius[c.i] + p.radius[c.j]));
    bonds.push_back(make_bond(c.i, c.j, p.id[c.i], p.id[c.j], p.pos[c.i], p.radius[c.i], p.pos[c.j],
                              p.radius[c.j], k.kr_n_m, k.ks_n_m, k.kb_nm_rad, k.kt_nm_rad, fr0,
                              fs0));
  }
  return bonds;
}

}  // namespace rockcal
