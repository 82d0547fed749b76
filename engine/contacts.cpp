#include "engine/contacts.hpp"

namespace rockcal {
namespace {

// Out of line so that the sliding contact's arithmetic compiles as it did without rolling
// resistance: a job without the effect gives the same numbers, to the last bit, as before it.
[[gnu::noinline]] void add_rolling_moment(ContactPair& c, Particles& p, const ContactLaw& law,
                                          const Vec3& n, double touch, double fn, double dt) {
  const double r_star = p.radius[c.i] * p.radius[c.j] / touch;
  const Vec3 w = p.omega[c.j] - p.omega[c.i];
  Vec3 th = c.roll - c.roll.dot(n) * n;  // kept in the tangent plane, like the spring
  const double th_old = c.roll.norm(), th_new = th.norm();
  if (th_new > 0) th *= th_old / th_new;
  th += (w - w.dot(n) * n) * dt;
  const double k_roll = rolling_stiffness_per_r2(law) * r_star * r_star;
  Vec3 m = -k_roll * th;  // on j
  const double m_limit = law.rolling_friction * r_star * fn, m_norm = m.norm();
  if (m_norm > m_limit) {
    m *= m_limit / m_norm;
    th = -m / k_roll;
  }
  c.roll = th;
  p.torque[c.j] += m;
  p.torque[c.i] -= m;
}

}  // namespace

void accumulate_contact_forces(NeighbourList& nl, Particles& p, const ContactLaw& law, double dt) {
  for (ContactPair& c : nl.pairs) {
    if (c.bond == PairBond::intact) continue;
    const Vec3 d = p.pos[c.j] - p.pos[c.i];
    const double dist2 = d.squaredNorm();
    const double touch = p.radius[c.i] + p.radius[c.j];
    if (dist2 >= touch * touch) {
      c.spring.setZero();
      c.roll.setZero();
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

    if (law.rolling_friction > 0.0)  // one predictable branch: off costs the loop nothing
      add_rolling_moment(c, p, law, n, touch, fn, dt);
  }
}

}  // namespace rockcal
