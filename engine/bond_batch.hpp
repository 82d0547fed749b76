// The bond kernel a batch of bonds at a time, for the time step. Each field is an array over the
// batch's lanes, and every lane runs the same branch-free arithmetic, so the compiler issues it as
// SIMD instructions: the divider and square-root unit, which bounds the one-bond-at-a-time kernel,
// then works on several bonds per instruction.
//
// It computes what bond_load does (without the energy) to round-off, plus eq. 2's left-hand side.
// A lane whose rotation falls outside the series that replaces atan2 (a bond rotated by more than
// about 11 degrees, so near breaking or broken) is flagged, and the caller evaluates that bond with
// bond_load instead: every bond gets the same treatment wherever it is evaluated, so both ranks
// that hold a border bond take the same breakage decision.
#pragma once

#include "engine/bonds.hpp"

namespace rockcal {

constexpr int kBondLanes = 8;

struct BondBatchIn {
  double d[3][kBondLanes];   // x_j - x_i, m
  double qi[4][kBondLanes];  // orientation of i: x, y, z, w
  double qj[4][kBondLanes];
  double n0[3][kBondLanes];
  double r0[kBondLanes], w_i[kBondLanes];
  double kr[kBondLanes], ks[kBondLanes], kb[kBondLanes], kt[kBondLanes];
  double inv_fr0[kBondLanes], inv_fs0[kBondLanes], inv_gt0[kBondLanes], inv_gb0[kBondLanes];
};

struct BondBatchOut {
  double force_i[3][kBondLanes];   // N; the force on j is the opposite
  double torque_i[3][kBondLanes];  // N m
  double torque_j[3][kBondLanes];
  double index[kBondLanes];  // left-hand side of eq. 2
  double exact[kBondLanes];  // 1 or 0 (a double: a byte-wide flag stops the vectoriser); 0:
                             // evaluate this bond with bond_load instead
};

// Copies bond `b` and its particles' state into lane `lane`.
void gather_bond(const Bond& b, const Particles& p, int lane, BondBatchIn& in);

void load_batch(const BondBatchIn& in, const BreakRule& rule, BondBatchOut& out);

}  // namespace rockcal
