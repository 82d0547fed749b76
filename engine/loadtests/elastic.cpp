#include <cmath>
#include <limits>
#include <unordered_map>

#include "engine/effects/effect.hpp"
#include "engine/loadtests/driver.hpp"
#include "engine/loadtests/interior.hpp"
#include "engine/loadtests/run_clock.hpp"
#include "engine/loadtests/specimen.hpp"
#include "engine/units.hpp"

namespace rockcal {
namespace {

constexpr double kHoldTransits = 20.0;        // held this long (at least) to let the damping settle
constexpr double kSettledEnergyRatio = 1e-8;  // kinetic / stored energy that counts as at rest
constexpr double kMaxSeatRadii = 2.0;  // seating closes the platens by at most this many radii

}  // namespace

// The specimen is compressed to the elastic strain (stage 1), held until at rest, then to twice
// that strain (stage 2). E and nu come from the increments between the two stages, so whatever
// seating the first stage needed (a random packing's rough ends) does not count; for a lattice the
// two stages are proportional and the result is the same as from stage 2 alone.
TestResult run_elastic_test(const JobSpec& job, const RunHooks& hooks) {
  const JobSpec spec = effective_spec(job);
  Simulation sim = make_specimen(spec, hooks.comm);
  RunClock clock(hooks, spec.output.progress_seconds);
  const double length = spec.sample.height_m;
  const double diameter = spec.sample.diameter_m;

  const double transit_s = wave_transit_time(spec);
  const double t_load = kElasticLoadTransits * transit_s;
  const double t_hold_min = kHoldTransits * transit_s;
  const double t_hold_max = kElasticHoldLimitTransits * transit_s;
  const std::int64_t max_steps =
      spec.loading.max_steps.value_or(std::numeric_limits<std::int64_t>::max());

  std::unordered_map<std::int64_t, Vec3> reference;  // by id: local indices change at rebuilds
  for (std::size_t k = 0; k < sim.particles.n_owned; ++k)
    reference.emplace(sim.particles.id[k], sim.particles.pos[k]);
  Wall& bottom = sim.walls[kBottomPlaten];
  Wall& top = sim.walls[kTopPlaten];
  const double gap0 = top.point.z() - bottom.point.z();
  const double stage_closure = spec.loading.elastic_strain * length;

  TestResult r;
  r.test = TestKind::elastic;
  count_specimen(sim, r);
  r.dt_s = sim.dt;
  double load = 0.0, closure = 0.0;
  int stage = 1;
  bool hit_hold_limit = false;
  auto progress = [&](double elapsed) {
    const double f =
        (stage - 1 +
         std::min(1.0, (sim.time - (stage - 1) * (t_load + t_hold_min)) / (t_load + t_hold_min))) /
        2;
    return Progress{sim.step, std::min(1.0, f), load, r.peak_load_n, sim.broken_total, elapsed};
  };

  // Closes the platens by `delta` more (half-cosine profile: no jolt at either end) and holds until
  // the specimen is at rest. Returns false if the run was stopped.
  auto compress_and_settle = [&](double delta) {
    const double t0 = sim.time;
    while (true) {
      const double t = sim.time + 0.5 * sim.dt - t0;
      const double speed =
          t < t_load ? 0.5 * delta * M_PI / t_load * std::sin(M_PI * t / t_load) : 0.0;
      bottom.velocity = Vec3(0, 0, 0.5 * speed);
      top.velocity = Vec3(0, 0, -0.5 * speed);
      sim.advance();
      closure = gap0 - (top.point.z() - bottom.point.z());
      load = 0.5 * (top.reaction.z() - bottom.reaction.z());
      r.peak_load_n = std::max(r.peak_load_n, load);
      if (sim.step % 50 == 0)
        r.curve.push_back({sim.step, sim.time, closure, load, sim.broken_total});
      clock.maybe_report(progress);
      const double held = sim.time - t0 - t_load;
      if (held > t_hold_min && sim.step % 50 == 0) {
        double energy[2] = {kinetic_energy(sim.particles), bond_energy(sim.bonds, sim.particles)};
        reduce_sum(sim.domain, energy, 2);
        if (energy[0] <= kSettledEnergyRatio * energy[1]) return true;
        if (held > t_hold_max) {
          hit_hold_limit = true;  // measured all the same, but not fully at rest
          return true;
        }
      }
      if (sim.step >= max_steps)
        r.stop_reason = "max_steps";
      else if (sim.stop_global)
        r.stop_reason = "cancelled";
      if (!r.stop_reason.empty()) return false;
      sim.stop_local = clock.stop_requested();  // decided together after the next step
    }
  };

  // Interior: the central half of the specimen in radius and in height. A lattice's volume per
  // particle is exact; a random packing's is counted in the core (2 radii clear of every surface).
  double volume_per_particle = particle_volume(spec);
  if (spec.sample.packing != "fcc") {
    const double clear = 2.0 * spec.sample.radius_m * spec.sample.radius_ratio;
    const double rc = 0.5 * diameter - clear, zc = 0.5 * length - clear;
    double count = 0.0;
    for (const auto& [id, x] : reference)
      count += (x.x() * x.x() + x.y() * x.y() <= rc * rc && std::abs(x.z()) <= zc);
    reduce_sum(sim.domain, &count, 1);
    if (count > 0) volume_per_particle = M_PI * rc * rc * 2.0 * zc / count;
  }
  InteriorScratch scratch;
  auto measure = [&] {
    return measure_interior(sim, reference, central_half(spec), volume_per_particle, scratch);
  };

  // A random packing's ends are rough by about a grain: at the elastic strain the platens would
  // touch a few protruding grains only. Seat them first: close slowly until the platen load reaches
  // what one stage should add (the lattice estimate), then let the specimen come to rest. Only the
  // increments of the two stages after that enter E and nu.
  bool ok = true;
  if (spec.sample.packing != "fcc") {
    const BondStiffness k = bond_stiffness(spec, spec.sample.radius_m);
    const double e_lattice =
        2.0 * (1.0 - 2.0 * spec.material.nu) * k.kr_n_m / (std::sqrt(2.0) * spec.sample.radius_m);
    const double seat_load =
        e_lattice * spec.loading.elastic_strain * 0.25 * M_PI * diameter * diameter;
    const double max_seat = kMaxSeatRadii * spec.sample.radius_m * spec.sample.radius_ratio;
    // Ten times a stage's mean speed: still slow against the wave speed, and the hold that follows
    // removes what little ringing it leaves.
    const double seat_speed = 10.0 * stage_closure / t_load;
    while (ok && load < seat_load && closure < max_seat) {
      bottom.velocity = Vec3(0, 0, 0.5 * seat_speed);
      top.velocity = Vec3(0, 0, -0.5 * seat_speed);
      sim.advance();
      closure = gap0 - (top.point.z() - bottom.point.z());
      load = 0.5 * (top.reaction.z() - bottom.reaction.z());
      if (sim.step % 50 == 0)
        r.curve.push_back({sim.step, sim.time, closure, load, sim.broken_total});
      clock.maybe_report(progress);
      if (sim.step >= max_steps || sim.stop_global) ok = false;
      sim.stop_local = clock.stop_requested();
    }
    if (!ok) r.stop_reason = sim.stop_global ? "cancelled" : "max_steps";
    ok = ok && compress_and_settle(0.0);
  }
  ok = ok && compress_and_settle(stage_closure);
  const InteriorState first = ok ? measure() : InteriorState{};
  stage = 2;
  ok = ok && compress_and_settle(stage_closure);
  if (ok) {
    const InteriorState second = measure();
    const Mat3 d_strain = second.strain - first.strain, d_stress = second.stress - first.stress;
    const double eps_axial = axial_component(d_strain);
    const double eps_lateral = lateral_component(d_strain);
    if (second.particles >= 4 && eps_axial != 0) {
      r.youngs_modulus_pa = d_stress(2, 2) / eps_axial;
      r.poisson_ratio = -eps_lateral / eps_axial;
    }
    r.stop_reason = hit_hold_limit ? "hold_limit" : "settled";
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
