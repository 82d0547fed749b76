// Two bonded particles along z with the seed's model-unit stiffnesses.
#pragma once

#include "engine/bonds.hpp"
#include "engine/units.hpp"

namespace rockcal::testing {

struct Pair {
  double r = 1.0;
  BondStiffness k = stiffness_from_kr(8000.0, 0.2, 1.0);
  Vec3 xi{0, 0, 0}, xj{0, 0, 2};
  Quat qi = Quat::Identity(), qj = Quat::Identity();
  Bond bond =
      make_bond(0, 1, 0, 1, xi, r, xj, r, k.kr_n_m, k.ks_n_m, k.kb_nm_rad, k.kt_nm_rad, 64.0, 64.0);

  BondLoad load() const { return bond_load(bond, xi, qi, xj, qj); }
};

inline Quat rot(double angle, const Vec3& axis) {
  return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

}  // namespace rockcal::testing
