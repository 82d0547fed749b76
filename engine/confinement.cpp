#include "engine/confinement.hpp"

#include <cmath>

namespace rockcal {

std::int64_t mark_confined(Particles& p, double inner_radius) {
  std::int64_t n = 0;
  for (std::size_t k = 0; k < p.n_owned; ++k) {
    const double r = std::hypot(p.pos[k].x(), p.pos[k].y());
    p.confined[k] = r > inner_radius ? 1 : 0;
    n += p.confined[k];
  }
  return n;
}

void accumulate_confining_forces(Particles& p, double force_n) {
  for (std::size_t k = 0; k < p.n_owned; ++k) {
    if (!p.confined[k]) continue;
    const double x = p.pos[k].x(), y = p.pos[k].y();
    const double r = std::hypot(x, y);
    if (r > 0) p.force[k] -= (force_n / r) * Vec3(x, y, 0.0);
  }
}

}  // namespace rockcal
