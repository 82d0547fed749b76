#include "engine/walls.hpp"

namespace rockcal {

Wall make_wall(const Vec3& normal, const Vec3& point, double kn, double ks, double friction,
               int slot) {
  Wall w;
  w.normal = normal.normalized();
  w.point = point;
  w.velocity = Vec3::Zero();
  w.kn_n_m = kn;
  w.ks_n_m = ks;
  w.friction = friction;
  w.slot = slot;
  w.reaction = Vec3::Zero();
  return w;
}

void accumulate_wall_forces(Wall& w, Particles& p, double dt) {
  Vec3 reaction = Vec3::Zero();
  const bool frictional = w.friction > 0;
  for (std::size_t k = 0; k < p.n_owned; ++k) {
    const double overlap = p.radius[k] - (p.pos[k] - w.point).dot(w.normal);
    if (overlap <= 0) {
      if (frictional) p.wall_spring[k][w.slot].setZero();
      continue;
    }
    const double fn = w.kn_n_m * overlap;
    Vec3 f = fn * w.normal;
    if (frictional) {
      const Vec3 r = -p.radius[k] * w.normal;  // centre -> contact point
      const Vec3 v_rel = p.vel[k] + p.omega[k].cross(r) - w.velocity;
      Vec3 s = p.wall_spring[k][w.slot] + (v_rel - v_rel.dot(w.normal) * w.normal) * dt;
      Vec3 ft = -w.ks_n_m * s;
      const double limit = w.friction * fn, ft_norm = ft.norm();
      if (ft_norm > limit) {
        ft *= limit / ft_norm;
        s = -ft / w.ks_n_m;
      }
      p.wall_spring[k][w.slot] = s;
      f += ft;
      p.torque[k] += r.cross(ft);
    }
    p.force[k] += f;
    reaction -= f;
  }
  w.reaction = reaction;
}

}  // namespace rockcal
