#include <cmath>
#include <limits>
#include <unordered_map>

#include "engine/loadtests/driver.hpp"
#include "engine/loadtests/interior.hpp"
#include "engine/loadtests/run_clock.hpp"
#include "engine/loadtests/specimen.hpp"
#include "engine/units.hpp"

namespace rockcal {
namespace {

constexpr double kLoadTransits = 20.0;  // loading time in elastic-wave transit times: quasi-static
constexpr double kHoldTransits = 20.0;  // then held this long (at least) to let the damping settle
constexpr double kSettledEnergyRatio = 1e-8;  // kinetic / stored energy that counts as at rest

}  // namespace

TestResult run_elastic_test(const JobSpec& spec, const RunHooks& hooks) {
  Simulation sim = make_specimen(spec, hooks.comm);
  RunClock clock(hooks, spec.output.progress_seconds);
  const double length = spec.sample.height_m;
  const double diameter = spec.sample.diameter_m;

  const double transit_s = wave_transit_time(spec);
  const double t_load = kLoadTransits * transit_s;
  const double t_hold_min = kHoldTransits * transit_s;
  const std::int64_t max_steps =
      spec.loading.max_steps.value_or(std::numeric_limits<std::int64_t>::max());

  std::unordered_map<std::int64_t, Vec3> reference;  // by id: local indices change at rebuilds
  for (std::size_t k = 0; k < sim.particles.n_owned; ++k)
    reference.emplace(sim.particles.id[k], sim.particles.pos[k]);
  Wall& bottom = sim.walls[kBottomPlaten];
  Wall& top = sim.walls[kTopPlaten];
  const double gap0 = top.point.z() - bottom.point.z();
  const double closure_target = spec.loading.elastic_strain * length;

  TestResult r;
  r.test = TestKind::elastic;
  count_specimen(sim, r);
  r.dt_s = sim.dt;
  double load = 0.0, closure = 0.0;
  auto progress = [&](double elapsed) {
    return Progress{sim.step,
                    std::min(1.0, sim.time / (t_load + t_hold_min)),
                    load,
                    r.peak_load_n,
                    sim.broken_total,
                    elapsed};
  };

  while (true) {
    // Half-cosine closure profile: zero speed at both ends, so the platens stop without a jolt.
    const double t_mid = sim.time + 0.5 * sim.dt;
    const double speed =
        t_mid < t_load ? 0.5 * closure_target * M_PI / t_load * std::sin(M_PI * t_mid / t_load)
                       : 0.0;
    bottom.velocity = Vec3(0, 0, 0.5 * speed);
    top.velocity = Vec3(0, 0, -0.5 * speed);
    sim.advance();
    closure = gap0 - (top.point.z() - bottom.point.z());
    load = 0.5 * (top.reaction.z() - bottom.reaction.z());
    r.peak_load_n = std::max(r.peak_load_n, load);
    if (sim.step % 50 == 0)
      r.curve.push_back({sim.step, sim.time, closure, load, sim.broken_total});
    clock.maybe_report(progress);

    if (sim.time > t_load + t_hold_min && sim.step % 50 == 0) {
      double energy[2] = {kinetic_energy(sim.particles), bond_energy(sim.bonds, sim.particles)};
      reduce_sum(sim.domain, energy, 2);
      if (energy[0] <= kSettledEnergyRatio * energy[1]) {
        r.stop_reason = "settled";
        break;
      }
    }
    if (sim.step >= max_steps)
      r.stop_reason = "max_steps";
    else if (clock.stop_requested())
      r.stop_reason = "cancelled";
    if (!r.stop_reason.empty()) break;
  }

  // Interior: the central half of the specimen in radius and in height.
  const double r_in = 0.25 * diameter, z_in = 0.25 * length;
  const InteriorState s = measure_interior(
      sim, reference,
      [&](const Vec3& x) {
        return x.x() * x.x() + x.y() * x.y() <= r_in * r_in && std::abs(x.z()) <= z_in;
      },
      particle_volume(spec));
  const double eps_axial = s.strain(2, 2);
  const double eps_lateral = 0.5 * (s.strain(0, 0) + s.strain(1, 1));
  if (s.particles >= 4 && eps_axial != 0) {
    r.youngs_modulus_pa = s.stress(2, 2) / eps_axial;
    r.poisson_ratio = -eps_lateral / eps_axial;
  }
  r.strength_pa = 0.0;
  r.peak_displacement_m = closure;
  r.steps = sim.step;
  r.broken_bonds = sim.broken_total;
  for (const BreakEvent& e : sim.breaks) ++r.broken_by[static_cast<int>(e.mode)];
  r.breaks = std::move(sim.breaks);
  r.wall_seconds = clock.elapsed_s();
  clock.maybe_report(progress, true);
  return r;
}

}  // namespace rockcal
