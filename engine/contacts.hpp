// Frictional contact between unbonded particles that touch: linear normal spring on the overlap,
// tangential spring with a Coulomb limit (its history lives in the neighbour list).
#pragma once

#include "engine/neighbours.hpp"

namespace rockcal {

struct ContactLaw {
  double kn_n_m;           // normal stiffness (the bond's K_r)
  double ks_n_m;           // tangential stiffness (the bond's K_s)
  double friction;         // Coulomb coefficient between particles never bonded
  double broken_friction;  // ... between particles whose bond broke
};

void accumulate_contact_forces(NeighbourList& nl, Particles& p, const ContactLaw& law, double dt);

}  // namespace rockcal
