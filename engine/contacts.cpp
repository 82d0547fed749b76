#include "engine/contacts.hpp"

namespace rockcal {

void accumulate_contact_forces(NeighbourList& nl, Particles& p, const ContactLaw& law, double dt) {
  for (ContactPair& c : nl.pairs) {
    if (c.bond == PairBond::intact) continue;
    const Vec3 d = p.pos[c.j] - p.pos[c.i];
    const double dist2 = d.squaredNorm();
    const double touch = p.radius[c.i] + p.radius[c.j];
    if (dist2 >= touch * touch) {
      c.spring.setZero();
      continue;
    }
    const double dist = std::sqrt(dist2);
    const Vec3 n = d / dist;  // i -> j
    const double overlap = touch - dist;
    const double fn = law.kn_n_m * overlap;  // repulsive

    // Relative velocity of j's surface point against i's at the contact.
    const Vec3 v_rel = (p.vel[c.j] - p.radius[c.j] * p.omega[c.j].cross(n)) -
                       (p.vel[c.i] + p.radius[c.i] * p.omega[c.i].cross(n));
    const Vec3 v_t = v_rel - v_rel.dot(n) * n;
    // Keep the spring in the current tangent plane (the pair rotates), then add the increment.
    Vec3 s = c.spring - c.spring.dot(n) * n;
    const double s_old = c.spring.norm(), s_new = s.norm();
    if (s_new > 0) s *= s_old / s_new;
    s += v_t * dt;
    Vec3 ft = -law.ks_n_m * s;  // on j
    const double mu = c.bond == PairBond::broken ? law.broken_friction : law.friction;
    const double limit = mu * fn;
    const double ft_norm = ft.norm();
    if (ft_norm >
        limit) {  // sliding: the spring stretches no further than the Coulomb limit allows
      ft *= limit / ft_norm;
      s = -ft / law.ks_n_m;
    }
    c.spring = s;

    const Vec3 f_j = fn * n + ft;
    p.force[c.j] += f_j;
    p.force[c.i] -= f_j;
    p.torque[c.j] += (-p.radius[c.j] * n).cross(ft);
    p.torque[c.i] += (p.radius[c.i] * n).cross(-ft);
  }
}

}  // namespace rockcal
