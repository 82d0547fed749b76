// Frictional contact between unbonded particles that touch: linear normal spring on the overlap,
// tangential spring with a Coulomb limit, and optionally a rolling-resistance spring with a moment
// limit (their history lives in the neighbour list).
#pragma once

#include "engine/neighbours.hpp"

namespace rockcal {

struct ContactLaw {
  double kn_n_m;           // normal stiffness (the bond's K_r)
  double ks_n_m;           // tangential stiffness (the bond's K_s)
  double friction;         // Coulomb coefficient between particles never bonded
  double broken_friction;  // ... between particles whose bond broke
  // Rolling resistance (Iwashita & Oda 1998; Ai et al. 2011's elastic-plastic spring, "type C"):
  // a moment against the pair's relative rotation, stiffness 2.25 k_n mu_r^2 R*^2, capped at
  // mu_r R* F_n (R* = R_i R_j / (R_i + R_j)). Angular grains resist rolling; spheres do not.
  // 0 = none, the seed's model.
  double rolling_friction = 0.0;
};

// The rolling spring's stiffness per R*^2 (N m / rad per m^2): Ai et al.'s choice, which makes the
// moment reach its limit after a relative rotation of about 1 / (2.25 mu_r) x the overlap / R*.
inline double rolling_stiffness_per_r2(const ContactLaw& law) {
  return 2.25 * law.kn_n_m * law.rolling_friction * law.rolling_friction;
}

void accumulate_contact_forces(NeighbourList& nl, Particles& p, const ContactLaw& law, double dt);

}  // namespace rockcal
