// Undamped small vibration of a bonded FCC block: total energy is conserved to second order in dt.
#include <gtest/gtest.h>

#include <random>

#include "engine/loadtests/specimen.hpp"
#include "engine/units.hpp"

using namespace rockcal;

namespace {

JobSpec block_spec() {
  JobSpec s;
  s.test = TestKind::uct;
  s.sample.diameter_m = 8;
  s.sample.height_m = 10;
  s.material.kr_n_m = 8000;
  s.damping = {0.0, 0.0};
  return s;
}

struct EnergyError {
  double worst;  // largest relative deviation from the initial energy
  double drift;  // relative change of the mean energy between the first and the last tenth
};

// Total energy history of a free block set vibrating by random small velocities.
EnergyError energy_error(double dt, std::int64_t steps) {
  JobSpec spec = block_spec();
  spec.loading.dt_s = dt;
  Simulation sim = make_specimen(spec);
  sim.walls.clear();  // free block
  std::mt19937 rng(42);
  std::normal_distribution<double> g(0.0, 1e-3);
  for (std::size_t k = 0; k < sim.particles.size(); ++k) {
    sim.particles.vel[k] = Vec3(g(rng), g(rng), g(rng));
    sim.particles.omega[k] = Vec3(g(rng), g(rng), g(rng));
  }
  sim.initialise();
  auto total = [&] {
    return kinetic_energy(sim.particles) + bond_energy(sim.bonds, sim.particles);
  };
  const double e0 = total();
  EnergyError err{0.0, 0.0};
  const std::int64_t tenth = steps / 10;
  double first = 0.0, last = 0.0;
  for (std::int64_t s = 0; s < steps; ++s) {
    sim.advance();
    const double e = total();
    err.worst = std::max(err.worst, std::abs(e - e0) / e0);
    if (s < tenth) first += e / tenth;
    if (s >= steps - tenth) last += e / tenth;
  }
  err.drift = std::abs(last - first) / e0;
  EXPECT_TRUE(sim.broken.empty());
  return err;
}

}  // namespace

TEST(Energy, DriftBelowTenthOfAPercentOverTenThousandSteps) {
  const JobSpec spec = block_spec();
  // At the default step (half the critical one) Verlet's bounded oscillation of the energy is a few
  // percent, but nothing accumulates; at a sixth of that step even the oscillation is below 0.1%.
  const EnergyError coarse = energy_error(0.5 * critical_time_step(spec), 10'000);
  EXPECT_LT(coarse.drift, 1e-3);
  const EnergyError fine = energy_error(0.08 * critical_time_step(spec), 10'000);
  EXPECT_LT(fine.worst, 1e-3);
  EXPECT_LT(fine.drift, 1e-4);
  RecordProperty("drift_at_default_dt", std::to_string(coarse.drift));
  RecordProperty("worst_at_0.08_critical_dt", std::to_string(fine.worst));
}

TEST(Energy, ErrorFallsAtSecondOrderWithTheTimeStep) {
  JobSpec spec = block_spec();
  const double dt = 0.4 * critical_time_step(spec);
  const double coarse = energy_error(dt, 2000).worst;
  const double fine = energy_error(0.5 * dt, 4000).worst;  // same simulated time
  const double order = std::log2(coarse / fine);
  RecordProperty("observed_order", std::to_string(order));
  EXPECT_GT(order, 1.7);
  EXPECT_LT(order, 2.3);
}
