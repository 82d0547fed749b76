#include "engine/bonds.hpp"

#include <algorithm>
#include <cmath>

#include "engine/bond_batch.hpp"

namespace rockcal {
namespace {

// atan2(y, x) for x >= 0. Intact bonds rotate little, so the common case |y| << x takes a Taylor
// series that is exact to rounding (|y/x| < 0.1: the first omitted term is below 1e-16 relative),
// at a fraction of the cost of the library call that otherwise dominates the time step.
inline double positive_atan2(double y, double x) {
  if (std::abs(y) < 0.1 * x) {
    const double z = y / x, z2 = z * z;
    return z * (1.0 - z2 * (1.0 / 3 -
                            z2 * (1.0 / 5 -
                                  z2 * (1.0 / 7 - z2 * (1.0 / 9 - z2 * (1.0 / 11 - z2 / 13))))));
  }
  return std::atan2(y, x);
}

}  // namespace

const char* to_string(BreakMode mode) {
  switch (mode) {
    case BreakMode::tension:
      return "tension";
    case BreakMode::shear:
      return "shear";
    case BreakMode::twist:
      return "twist";
    case BreakMode::bending:
      return "bending";
  }
  return "?";
}

Bond make_bond(std::int32_t i, std::int32_t j, std::int64_t id_i, std::int64_t id_j,
               const Vec3& x_i, double r_i, const Vec3& x_j, double r_j, double kr, double ks,
               double kb, double kt, double fr0, double fs0) {
  Bond b;
  b.i = i;
  b.j = j;
  b.id_i = id_i;
  b.id_j = id_j;
  const Vec3 d = x_j - x_i;
  b.r0 = d.norm();
  b.n0 = d / b.r0;
  b.w_i = r_i / (r_i + r_j);
  b.kr = kr;
  b.ks = ks;
  b.kb = kb;
  b.kt = kt;
  const double r_mean = 0.5 * (r_i + r_j);
  set_strengths(b, fr0, fs0, r_mean * fr0 / 4.0, r_mean * fs0 / 2.0);
  return b;
}

// The bond kernel: most of a time step is spent here. The divider (division and square root) is
// its bottleneck, so each result is formed with as few of them as the formulas allow: one
// reciprocal per normalisation, the bending axis's norm from |axis| = tn |v_perp|, |tau_b| from the
// bending angle. kWithEnergy: the stored energy is wanted (energy checks, not the time step).
template <bool kWithEnergy>
[[gnu::always_inline]] inline BondLoad load_kernel(const Bond& b, const Vec3& x_i, const Quat& q_i,
                                                   const Vec3& x_j, const Quat& q_j) {
  BondLoad out;
  const Vec3 d = x_j - x_i;
  const double len = d.norm();
  const Vec3 n = d * (1.0 / len);

  // Normal: tension positive; the force on i points to j when stretched.
  const double stretch = len - b.r0;
  out.f_r = b.kr * stretch;
  const Vec3 f_normal = out.f_r * n;

  // Shear: deviation of n from the body-carried reference direction.
  const double w_j = 1.0 - b.w_i;
  const Vec3 m_raw = b.w_i * (q_i * b.n0) + w_j * (q_j * b.n0);
  const Vec3 m = m_raw * (1.0 / m_raw.norm());
  const Vec3 ds = b.r0 * (m.dot(n) * n - m);  // displacement of j off the reference, normal to n
  const Vec3 f_shear = b.ks * ds;             // on i (and -f_shear on j)
  const double ds_sq = ds.squaredNorm();
  out.f_s = b.ks * std::sqrt(ds_sq);

  out.force_i = f_normal + f_shear;
  out.force_j = -out.force_i;
  // The shear force acts at the contact point: lever w_i L from i, w_j L from j (angular momentum
  // is conserved exactly because the levers add up to the current distance).
  const Vec3 shear_moment = len * n.cross(f_shear);
  out.torque_i = b.w_i * shear_moment;
  out.torque_j = w_j * shear_moment;

  // Twist and bending from the relative rotation q = (w, v), split about the current bond axis as
  // q = swing * twist. In closed form: twist angle 2 atan2(v.n, w); swing angle
  // 2 atan2(|v_perp|, sqrt(w^2 + (v.n)^2)) about the axis (w v_perp - (v.n) v x n) / |...|, whose
  // norm is sqrt(w^2 + (v.n)^2) |v_perp|.
  Quat rel = q_j * q_i.conjugate();
  if (rel.w() < 0) rel.coeffs() = -rel.coeffs();
  const Vec3 v = rel.vec();
  const double w = rel.w();
  const double p = v.dot(n);
  const Vec3 v_perp = v - p * n;
  const double s_perp = v_perp.norm();
  const double tn = std::sqrt(w * w + p * p);
  // At exactly 180 degrees of bending (tn = 0) the twist is undefined: take none.
  const double twist_angle = tn > 1e-12 ? 2.0 * positive_atan2(p, w) : 0.0;
  Vec3 bend = Vec3::Zero();
  double bend_angle = 0.0;
  const double axis_norm = tn * s_perp;
  if (axis_norm > 0) {
    const Vec3 axis = w * v_perp - p * v.cross(n);
    bend_angle = 2.0 * positive_atan2(s_perp, tn);
    bend = (bend_angle / axis_norm) * axis;
  }

  const double twist_torque = b.kt * twist_angle;
  const Vec3 tau = twist_torque * n + b.kb * bend;  // restoring torque on i; -tau on j
  out.tau_t = std::abs(twist_torque);
  out.tau_b = b.kb * bend_angle;
  out.torque_i += tau;
  out.torque_j -= tau;

  if constexpr (kWithEnergy) {
    out.energy = 0.5 * (b.kr * stretch * stretch + b.ks * ds_sq + b.kt * twist_angle * twist_angle +
                        b.kb * bend_angle * bend_angle);
  } else {
    out.energy = 0.0;
  }
  return out;
}

BondLoad bond_load(const Bond& b, const Vec3& x_i, const Quat& q_i, const Vec3& x_j,
                   const Quat& q_j) {
  return load_kernel<true>(b, x_i, q_i, x_j, q_j);
}

double breakage_index(const Bond& b, const BondLoad& load, const BreakRule& rule,
                      BreakMode* dominant) {
  const double f_r = load.f_r >= 0 ? load.f_r : rule.compression_coupling * load.f_r;
  const double terms[4] = {f_r * b.inv_fr0, load.f_s * b.inv_fs0, load.tau_t * b.inv_gt0,
                           load.tau_b * b.inv_gb0};
  if (dominant) {
    int k = 0;
    for (int t = 1; t < 4; ++t)
      if (terms[t] > terms[k]) k = t;
    *dominant = static_cast<BreakMode>(k);
  }
  return terms[0] + terms[1] + terms[2] + terms[3];
}

void accumulate_bond_forces(std::vector<Bond>& bonds, Particles& p, const BreakRule& rule,
                            std::int64_t step, std::vector<Bond>& broken,
                            std::vector<BreakEvent>& events) {
  BondBatchIn in;
  BondBatchOut out;
  const std::size_t n = bonds.size();
  std::size_t kept = 0;  // intact bonds move down over broken ones, keeping their locality order
  for (std::size_t first = 0; first < n; first += kBondLanes) {
    const int lanes = static_cast<int>(std::min<std::size_t>(kBondLanes, n - first));
    // A short last batch repeats its first bond in the idle lanes, so that every bond, whatever
    // its place in the list, goes through the same arithmetic.
    for (int l = 0; l < kBondLanes; ++l) gather_bond(bonds[first + (l < lanes ? l : 0)], p, l, in);
    load_batch(in, rule, out);

    for (int l = 0; l < lanes; ++l) {
      const Bond& b = bonds[first + l];
      const bool exact = out.exact[l] != 0.0;
      // The one-bond kernel: for lanes outside the batch's series, and for a break's mode.
      BondLoad load;
      if (!exact)
        load = load_kernel<false>(b, p.pos[b.i], p.orient[b.i], p.pos[b.j], p.orient[b.j]);
      const double index = exact ? out.index[l] : breakage_index(b, load, rule, nullptr);
      if (index >= 1.0) {
        if (exact)
          load = load_kernel<false>(b, p.pos[b.i], p.orient[b.i], p.pos[b.j], p.orient[b.j]);
        BreakMode mode;
        breakage_index(b, load, rule, &mode);
        if (static_cast<std::size_t>(b.i) < p.n_owned)
          events.push_back({step, b.id_i, b.id_j, 0.5 * (p.pos[b.i] + p.pos[b.j]), mode});
        broken.push_back(b);
        continue;
      }
      const Vec3 f_i =
          exact ? Vec3(out.force_i[0][l], out.force_i[1][l], out.force_i[2][l]) : load.force_i;
      const Vec3 t_i =
          exact ? Vec3(out.torque_i[0][l], out.torque_i[1][l], out.torque_i[2][l]) : load.torque_i;
      const Vec3 t_j =
          exact ? Vec3(out.torque_j[0][l], out.torque_j[1][l], out.torque_j[2][l]) : load.torque_j;
      p.force[b.i] += f_i;
      p.force[b.j] -= f_i;
      p.torque[b.i] += t_i;
      p.torque[b.j] += t_j;
      if (kept != first + l) bonds[kept] = b;  // every bond below first + l has been read
      ++kept;
    }
  }
  bonds.resize(kept);
}

double bond_energy(const std::vector<Bond>& bonds, const Particles& p) {
  double e = 0.0;
  for (const Bond& b : bonds)
    if (static_cast<std::size_t>(b.i) < p.n_owned)  // a border bond is counted by one rank only
      e += bond_load(b, p.pos[b.i], p.orient[b.i], p.pos[b.j], p.orient[b.j]).energy;
  return e;
}

}  // namespace rockcal
