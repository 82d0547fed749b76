#include "engine/bond_batch.hpp"

#include <cmath>

namespace rockcal {
namespace {

// Three scalars rather than an Eigen vector: plain values the vectoriser keeps in registers.
struct V {
  double x, y, z;
};
inline V operator+(V a, V b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline V operator-(V a, V b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline V operator*(double s, V a) {
  return {s * a.x, s * a.y, s * a.z};
}
inline double dot(V a, V b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline V cross(V a, V b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// The unit quaternion (u, w) applied to v.
inline V rotate(V u, double w, V v) {
  const V t = 2.0 * cross(u, v);
  return v + w * t + cross(u, t);
}

// atan(z) / z for z^2 < 0.01, exact to rounding there (the first omitted term is below 1e-16).
inline double atan_over_z(double z2) {
  return 1.0 - z2 * (1.0 / 3 -
                     z2 * (1.0 / 5 - z2 * (1.0 / 7 - z2 * (1.0 / 9 - z2 * (1.0 / 11 - z2 / 13)))));
}

}  // namespace

void gather_bond(const Bond& b, const Particles& p, int lane, BondBatchIn& in) {
  const Vec3& xi = p.pos[b.i];
  const Vec3& xj = p.pos[b.j];
  const Quat& qi = p.orient[b.i];
  const Quat& qj = p.orient[b.j];
  for (int a = 0; a < 3; ++a) {
    in.d[a][lane] = xj[a] - xi[a];
    in.n0[a][lane] = b.n0[a];
  }
  for (int a = 0; a < 4; ++a) {
    in.qi[a][lane] = qi.coeffs()[a];
    in.qj[a][lane] = qj.coeffs()[a];
  }
  in.r0[lane] = b.r0;
  in.w_i[lane] = b.w_i;
  in.kr[lane] = b.kr;
  in.ks[lane] = b.ks;
  in.kb[lane] = b.kb;
  in.kt[lane] = b.kt;
  in.inv_fr0[lane] = b.inv_fr0;
  in.inv_fs0[lane] = b.inv_fs0;
  in.inv_gt0[lane] = b.inv_gt0;
  in.inv_gb0[lane] = b.inv_gb0;
}

// The formulas are bond_load's (see bonds.cpp for the kinematics). Twist and bending angles use
// 2 atan(z) = 2 z (atan(z) / z), and the bending vector's scale, angle / (tn |v_perp|), becomes
// 2 (atan(z) / z) / tn^2, which needs no guard where the bending vanishes.
void load_batch(const BondBatchIn& in, const BreakRule& rule, BondBatchOut& out) {
  const double coupling = rule.compression_coupling;
#pragma GCC ivdep
  for (int l = 0; l < kBondLanes; ++l) {
    const V d{in.d[0][l], in.d[1][l], in.d[2][l]};
    const double len = std::sqrt(dot(d, d));
    const V n = (1.0 / len) * d;
    const double f_r = in.kr[l] * (len - in.r0[l]);

    const V n0{in.n0[0][l], in.n0[1][l], in.n0[2][l]};
    const V ui{in.qi[0][l], in.qi[1][l], in.qi[2][l]};
    const V uj{in.qj[0][l], in.qj[1][l], in.qj[2][l]};
    const double wi = in.qi[3][l], wj = in.qj[3][l];
    const double weight_i = in.w_i[l], weight_j = 1.0 - weight_i;
    const V m_raw = weight_i * rotate(ui, wi, n0) + weight_j * rotate(uj, wj, n0);
    const V m = (1.0 / std::sqrt(dot(m_raw, m_raw))) * m_raw;
    const V ds = in.r0[l] * (dot(m, n) * n - m);
    const V f_shear = in.ks[l] * ds;
    const double f_s = in.ks[l] * std::sqrt(dot(ds, ds));
    const V shear_moment = len * cross(n, f_shear);

    // Relative rotation q_j q_i^-1 = (v, w), taken with w >= 0.
    double w = wj * wi + dot(uj, ui);
    V v = wi * uj - wj * ui - cross(uj, ui);
    const double sign = w < 0 ? -1.0 : 1.0;
    w *= sign;
    v = sign * v;
    const double p = dot(v, n);
    const V v_perp = v - p * n;
    const double s_perp_sq = dot(v_perp, v_perp);
    const double tn_sq = w * w + p * p;

    const double zt = p / (w > 1e-300 ? w : 1e-300);  // (a select: fmax does not vectorise)
    const double twist_angle = 2.0 * zt * atan_over_z(zt * zt);
    const double inv_tn_sq = 1.0 / (tn_sq > 1e-300 ? tn_sq : 1e-300);
    const double zb_sq = s_perp_sq * inv_tn_sq;
    const double ratio_b = atan_over_z(zb_sq);
    const double bend_angle = 2.0 * std::sqrt(zb_sq) * ratio_b;
    const V axis = w * v_perp - p * cross(v, n);  // |axis| = tn |v_perp|

    const double twist_torque = in.kt[l] * twist_angle;
    const V tau = twist_torque * n + (in.kb[l] * 2.0 * ratio_b * inv_tn_sq) * axis;
    const V f_i = f_r * n + f_shear;
    const V t_i = weight_i * shear_moment + tau;
    const V t_j = weight_j * shear_moment - tau;
    out.force_i[0][l] = f_i.x;
    out.force_i[1][l] = f_i.y;
    out.force_i[2][l] = f_i.z;
    out.torque_i[0][l] = t_i.x;
    out.torque_i[1][l] = t_i.y;
    out.torque_i[2][l] = t_i.z;
    out.torque_j[0][l] = t_j.x;
    out.torque_j[1][l] = t_j.y;
    out.torque_j[2][l] = t_j.z;

    const double f_r_eff = f_r >= 0 ? f_r : coupling * f_r;
    out.index[l] = f_r_eff * in.inv_fr0[l] + f_s * in.inv_fs0[l] +
                   std::fabs(twist_torque) * in.inv_gt0[l] + in.kb[l] * bend_angle * in.inv_gb0[l];
    out.exact[l] = std::fabs(p) < 0.1 * w && zb_sq < 0.01 ? 1.0 : 0.0;
  }
}

}  // namespace rockcal
