// The seed's six-interaction bond (eq. 1) and its breakage rule (eq. 2).
//
// Kinematics (Wang's finite-deformation method, symmetric in the two particles):
// - normal: f_r = K_r (L - r0), positive in tension;
// - shear: each particle carries the initial bond direction n0 in its body frame; the reference
//   direction m is their radius-weighted mean in the world frame, and the shear displacement is
//   r0 times the component of the current direction n off m. Rigid rotation leaves it zero;
// - twist and bending: the relative rotation q_j q_i^-1 is split about the current bond axis into
//   twist (about n) and swing (about an axis normal to n). The split is unique, so it does not
//   depend on whether twist or bending was applied first, and it rotates with the pair.
// Bonds are created when orientations are the identity, so n0 is the same in both body frames.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/particles.hpp"

namespace rockcal {

enum class BreakMode : std::uint8_t { tension, shear, twist, bending };
const char* to_string(BreakMode mode);

struct Bond {
  std::int32_t i, j;        // local particle indices; i is the particle with the lower id, so every
                            // rank that holds the bond evaluates it with the same operands
  std::int64_t id_i, id_j;  // global particle ids, id_i < id_j
  double r0;                // rest length, m
  Vec3 n0;                  // bond direction i -> j at creation (= in both body frames), unit
  double w_i;               // R_i / (R_i + R_j): where the bond's contact point sits
  double kr, ks;            // N/m
  double kb, kt;            // N m / rad
  // Strengths: set them with set_strengths, which keeps the reciprocals eq. 2 multiplies by, so
  // the time step divides by none of them.
  double fr0, fs0;  // tensile and shear strengths, N
  double gb0, gt0;  // bending and twisting strengths, N m (G_b0 = R F_r0 / 4, G_t0 = R F_s0 / 2)
  double inv_fr0, inv_fs0, inv_gb0, inv_gt0;  // 1/N, 1/(N m)
};

inline void set_strengths(Bond& b, double fr0, double fs0, double gb0, double gt0) {
  b.fr0 = fr0;
  b.fs0 = fs0;
  b.gb0 = gb0;
  b.gt0 = gt0;
  b.inv_fr0 = 1.0 / fr0;
  b.inv_fs0 = 1.0 / fs0;
  b.inv_gb0 = 1.0 / gb0;
  b.inv_gt0 = 1.0 / gt0;
}

// The state of one bond at the current configuration: what eq. 1 gives and what eq. 2 weighs.
struct BondLoad {
  Vec3 force_i, force_j;    // N
  Vec3 torque_i, torque_j;  // N m
  double f_r;               // signed normal force, positive in tension
  double f_s;               // shear force magnitude
  double tau_t;             // twisting torque magnitude
  double tau_b;             // bending torque magnitude
  double energy;            // elastic energy stored in the bond, J
};

// How eq. 2 treats compression: 1 = signed f_r (compression raises the other terms' capacity),
// 0 = f_r clamped at zero in compression. Intermediate values interpolate.
struct BreakRule {
  double compression_coupling = 1.0;
};

BondLoad bond_load(const Bond& b, const Vec3& x_i, const Quat& q_i, const Vec3& x_j,
                   const Quat& q_j);

// Left-hand side of eq. 2 and its dominant term.
double breakage_index(const Bond& b, const BondLoad& load, const BreakRule& rule,
                      BreakMode* dominant);

// Creates a bond between two particles at their current (rest) configuration.
Bond make_bond(std::int32_t i, std::int32_t j, std::int64_t id_i, std::int64_t id_j,
               const Vec3& x_i, double r_i, const Vec3& x_j, double r_j, double kr, double ks,
               double kb, double kt, double fr0, double fs0);

struct BreakEvent {
  std::int64_t step;
  std::int64_t id_i, id_j;  // particle ids
  Vec3 where;               // bond midpoint, m
  BreakMode mode;
};

// Adds every intact bond's forces and torques to the particles; bonds that satisfy eq. 2 break
// (are removed from `bonds`) and are appended to `broken`. A break is recorded in `events` only by
// the rank that owns the bond's lower-id particle, so that a border bond is counted once.
void accumulate_bond_forces(std::vector<Bond>& bonds, Particles& p, const BreakRule& rule,
                            std::int64_t step, std::vector<Bond>& broken,
                            std::vector<BreakEvent>& events);

// Elastic energy of the bonds this rank counts (those whose lower-id particle it owns).
double bond_energy(const std::vector<Bond>& bonds, const Particles& p);

}  // namespace rockcal
