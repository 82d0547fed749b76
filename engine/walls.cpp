#include "engine/walls.hpp"

#include <cmath>

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

Wall make_jaw(const Vec3& normal, const Vec3& contact, const Vec3& axis, double radius,
              double half_angle, double kn, double ks, double friction, int slot) {
  Wall w = make_wall(normal, contact + radius * normal.normalized(), kn, ks, friction, slot);
  w.shape = WallShape::jaw;
  w.axis = axis.normalized();
  w.jaw_radius = radius;
  w.jaw_half_angle = half_angle;
  return w;
}

namespace {

// Where a particle meets a surface: how deep, and the surface normal there (into the specimen).
struct Touch {
  double overlap;
  Vec3 normal;
};

struct PlaneFace {
  const Wall& w;
  Touch operator()(const Vec3& x, double r) const {
    return {r - (x - w.point).dot(w.normal), w.normal};
  }
};

struct JawFace {
  const Wall& w;
  double cos_limit;
  Touch operator()(const Vec3& x, double r) const {
    Vec3 d = x - w.point;
    d -= d.dot(w.axis) * w.axis;  // from the axis to the centre, across it
    const double dist = d.norm();
    // Only the jaw's own face: beyond the axis opposite the normal, within its half-angle.
    if (dist <= 0.0 || -d.dot(w.normal) < cos_limit * dist) return {-1.0, w.normal};
    return {dist + r - w.jaw_radius, -d / dist};
  }
};

template <class Face>
void accumulate(Wall& w, Particles& p, double dt, const Face& face) {
  Vec3 reaction = Vec3::Zero();
  const bool frictional = w.friction > 0;
  for (std::size_t k = 0; k < p.n_owned; ++k) {
    const Touch t = face(p.pos[k], p.radius[k]);
    if (t.overlap <= 0) {
      if (frictional) p.wall_spring[k][w.slot].setZero();
      continue;
    }
    const double fn = w.kn_n_m * t.overlap;
    Vec3 f = fn * t.normal;
    if (frictional) {
      const Vec3 r = -p.radius[k] * t.normal;  // centre -> contact point
      const Vec3 v_rel = p.vel[k] + p.omega[k].cross(r) - w.velocity;
      Vec3 s = p.wall_spring[k][w.slot] + (v_rel - v_rel.dot(t.normal) * t.normal) * dt;
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

}  // namespace

void accumulate_wall_forces(Wall& w, Particles& p, double dt) {
  if (w.shape == WallShape::jaw)
    accumulate(w, p, dt, JawFace{w, std::cos(w.jaw_half_angle)});
  else
    accumulate(w, p, dt, PlaneFace{w});
}

}  // namespace rockcal
