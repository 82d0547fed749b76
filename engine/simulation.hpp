// The simulated system and one time step. Test drivers (loadtests/) set it up and steer the walls.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/bonds.hpp"
#include "engine/contacts.hpp"
#include "engine/domain.hpp"
#include "engine/integrator.hpp"
#include "engine/neighbours.hpp"
#include "engine/walls.hpp"

namespace rockcal {

struct Simulation {
  Particles particles;             // owned first, then ghosts
  std::vector<Bond> bonds;         // intact bonds with at least one owned particle
  std::vector<Bond> broken;        // broken ones, kept for output and post-break contact friction
  std::vector<BreakEvent> breaks;  // breaks this rank counts (see accumulate_bond_forces)
  NeighbourList neighbours;
  ContactLaw contact{};
  std::vector<Wall> walls;  // reactions are global (summed over ranks) after each step
  // Triaxial test: inward radial force on each confined particle (Particles::confined), N. Zero
  // for the other tests, which then pay one branch per step for it.
  double confining_force_n = 0.0;
  BreakRule break_rule;
  Damping damping;
  Domain domain;    // serial unless set up by make_specimen under MPI
  double dt = 0.0;  // s
  std::int64_t step = 0;
  double time = 0.0;              // s
  std::int64_t broken_total = 0;  // bonds broken so far, all ranks
  bool stop_local = false;        // set by a driver on any rank ...
  bool stop_global = false;       // ... and seen by all ranks after the next step
  std::int64_t floaters_removed = 0;  // set-up record: particles dropped before bonding

  // Exchanges ghosts, builds the neighbour list and computes the loads of the initial
  // configuration.
  void initialise();
  // One velocity-Verlet step: half kick, drift (particles and walls), loads, half kick.
  void advance();
  // Forces and torques of the current configuration (and the reductions every rank needs).
  void compute_loads();
  // Migration, ghost exchange, bond re-indexing and neighbour list: after particles moved far
  // enough.
  void redistribute();
};

// Bonds every pair of particles closer than (R_i + R_j)(1 + tolerance), with the stiffness of
// `stiffness_for_radius(mean radius)` and strengths fr0, fs0 (N).
template <class StiffnessFn>
std::vector<Bond> bond_neighbours(const Particles& p, double tolerance,
                                  StiffnessFn stiffness_for_radius, double fr0, double fs0);

// The largest stable step for the current bonds and walls (per-particle stiffness sums), times
// safety.
double auto_time_step(const Simulation& sim, double safety);

}  // namespace rockcal

#include "engine/bonding_impl.hpp"
