// The simulated system and one time step. Test drivers (loadtests/) set it up and steer the walls.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/bonds.hpp"
#include "engine/contacts.hpp"
#include "engine/integrator.hpp"
#include "engine/neighbours.hpp"
#include "engine/walls.hpp"

namespace rockcal {

struct Simulation {
  Particles particles;
  std::vector<Bond> bonds;   // intact
  std::vector<Bond> broken;  // broken, kept for output and post-break contact friction
  std::vector<BreakEvent> breaks;
  NeighbourList neighbours;
  ContactLaw contact{};
  std::vector<Wall> walls;
  BreakRule break_rule;
  Damping damping;
  double dt = 0.0;  // s
  std::int64_t step = 0;
  double time = 0.0;  // s

  // Builds the neighbour list and computes the loads of the initial configuration.
  void initialise();
  // One velocity-Verlet step: half kick, drift (particles and walls), loads, half kick.
  void advance();
  void compute_loads();
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
