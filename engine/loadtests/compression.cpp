#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "engine/confinement.hpp"
#include "engine/effects/effect.hpp"
#include "engine/loadtests/driver.hpp"
#include "engine/loadtests/gauges.hpp"
#include "engine/loadtests/loading_speed.hpp"
#include "engine/loadtests/modulus.hpp"
#include "engine/loadtests/peak.hpp"
#include "engine/loadtests/quasi_static_rerun.hpp"
#include "engine/loadtests/run_clock.hpp"
#include "engine/loadtests/seating.hpp"
#include "engine/loadtests/specimen.hpp"
#include "engine/loadtests/strength.hpp"

namespace rockcal {
namespace {

// Platen speed over time: a ramp up to the loading speed, then (two-rate loading) a ramp of the
// same length down to the slow speed once damage has started. The auto speed also ramps up to its
// late speed once the closure has passed the window of a bond-controlled peak.
constexpr double kRampTransits = 2.0;

struct SpeedSchedule {
  double fast_m_s, slow_factor, ramp_s;
  double late_m_s = 0.0;      // the speed past the window (auto speed only); <= fast_m_s: none
  double slow_from_s = -1.0;  // when the slow-down started; < 0 while intact
  double late_from_s = -1.0;  // when the speed-up started; < 0 before

  void slow_down_from(double t) {
    if (slow_from_s < 0 && slow_factor < 1.0) slow_from_s = t;
  }
  void speed_up_from(double t) {
    if (late_from_s < 0 && late_m_s > fast_m_s) late_from_s = t;
  }
  // How far a ramp that started at t0 has got at t (0 before it starts, 1 once over).
  double ramped(double t, double t0) const {
    if (t0 < 0 || t < t0) return 0.0;
    return ramp_s > 0 ? std::min(1.0, (t - t0) / ramp_s) : 1.0;
  }
  // True once the slow speed is reached: the fast phase's (partly inertial) peak no longer counts.
  bool slow_phase(double t) const { return slow_from_s >= 0 && t >= slow_from_s + ramp_s; }
  bool changing(double t) const {
    return t < ramp_s || (slow_from_s >= 0 && !slow_phase(t)) ||
           (late_from_s >= 0 && t < late_from_s + ramp_s);
  }
  double speed_at(double t) const {
    const double base = fast_m_s * ramped(t, 0.0) + (late_m_s - fast_m_s) * ramped(t, late_from_s);
    return base * (1.0 - (1.0 - slow_factor) * ramped(t, slow_from_s));
  }
};

// Triaxial confinement: the lateral-surface particles (centre farther than D/2 - 1.5 R from the
// axis) carry the pressure times the lateral area, shared equally. It is ramped in smoothly over
// kConfineRampTransits wave transits and held for kConfineHoldTransits more, with the platens
// still, so the platens start on a specimen at rest under the confinement.
constexpr double kConfineRampTransits = 3.0;
constexpr double kConfineHoldTransits = 1.0;
constexpr double kSurfaceDepthRadii = 1.5;

// Runs the confinement phase. Returns false when the run was stopped (cancelled or step limit).
bool confine(Simulation& sim, const JobSpec& spec, RunClock& clock, std::int64_t max_steps,
             const std::function<Progress(double)>& progress) {
  const double d = spec.sample.diameter_m, h = spec.sample.height_m;
  const double n_surface = sum_over_ranks(
      sim.domain, static_cast<double>(mark_confined(
                      sim.particles, 0.5 * d - kSurfaceDepthRadii * spec.sample.radius_m)));
  if (n_surface == 0) throw std::runtime_error("the triaxial specimen has no lateral surface");
  const double full_force = spec.loading.confining_pressure_pa * M_PI * d * h / n_surface;
  // Radially the wave crosses D, axially H: the slower of the two sets the pace.
  const double transit = wave_transit_time(spec) * std::max(1.0, d / h);
  const double t_ramp = kConfineRampTransits * transit;
  const double t_end = sim.time + t_ramp + kConfineHoldTransits * transit;
  const double t0 = sim.time;
  for (Wall& w : sim.walls) w.velocity.setZero();
  while (sim.time < t_end) {
    const double f = std::min(1.0, (sim.time + sim.dt - t0) / t_ramp);  // at the step's end
    sim.confining_force_n = full_force * 0.5 * (1.0 - std::cos(M_PI * f));
    sim.advance();
    clock.maybe_report(progress);
    if (sim.stop_global || sim.step >= max_steps) return false;
    sim.stop_local = clock.stop_requested();
  }
  sim.confining_force_n = full_force;
  return true;
}

// Seating: the platens close (speed ramped in) until the load, counted from `base_load`, reaches
// the seating load, then stand still for kSeatingHoldTransits transits. Returns "" once seated,
// else the stop reason.
std::string seat(Simulation& sim, const JobSpec& spec, RunClock& clock, std::int64_t max_steps,
                 double base_load, double t_ramp, Seating& seating,
                 const std::function<Progress(double)>& progress) {
  Wall& bottom = sim.walls[kBottomPlaten];
  Wall& top = sim.walls[kTopPlaten];
  const double length = loaded_length(spec);
  const double gap0 = top.point.z() - bottom.point.z();
  const SpeedSchedule approach{platen_speed(spec), 1.0, t_ramp};
  seating.load_n = seating_load(spec);
  double t = 0.0;
  for (;;) {
    const double v = approach.speed_at(t + 0.5 * sim.dt);
    bottom.velocity = Vec3(0, 0, v);
    top.velocity = Vec3(0, 0, -v);
    sim.advance();
    t += sim.dt;
    clock.maybe_report(progress);
    const double load = 0.5 * (top.reaction.z() - bottom.reaction.z()) - base_load;
    if (load >= seating.load_n) break;
    if (gap0 - (top.point.z() - bottom.point.z()) >= spec.loading.max_strain * length)
      return "not_seated";
    if (sim.step >= max_steps) return "max_steps";
    if (sim.stop_global) return "cancelled";
    sim.stop_local = clock.stop_requested();
  }
  for (Wall& w : sim.walls) w.velocity.setZero();
  const double t_hold = sim.time + kSeatingHoldTransits * wave_transit_time(spec);
  while (sim.time < t_hold) {
    sim.advance();
    clock.maybe_report(progress);
    if (sim.step >= max_steps) return "max_steps";
    if (sim.stop_global) return "cancelled";
    sim.stop_local = clock.stop_requested();
  }
  seating.step = sim.step;
  seating.broken_bonds = sim.broken_total;
  return "";
}

// The least-squares radial strain e of the particles in `reference` (by id, their positions then):
// u_r = e r over their radial displacements u_r at radii r from the loading axis, summed over
// ranks. Positive when they move outwards.
double radial_strain(const Simulation& sim,
                     const std::unordered_map<std::int64_t, Vec3>& reference) {
  const Particles& p = sim.particles;
  double sums[2] = {};  // sum u . r, sum r . r (in the x-y plane)
  for (std::size_t k = 0; k < p.n_owned; ++k) {
    const auto it = reference.find(p.id[k]);
    if (it == reference.end()) continue;
    const Vec3& x0 = it->second;
    const Vec3 u = p.pos[k] - x0;
    sums[0] += u.x() * x0.x() + u.y() * x0.y();
    sums[1] += x0.x() * x0.x() + x0.y() * x0.y();
  }
  reduce_sum(sim.domain, sums, 2);
  return sums[1] > 0 ? sums[0] / sums[1] : 0.0;
}

}  // namespace

void tally_breaks(const JobSpec& spec, TestResult& r) {
  r.broken_by = {};
  for (const BreakEvent& e : r.breaks) ++r.broken_by[static_cast<int>(e.mode)];
  if (spec.test == TestKind::btt)
    r.btt_fracture = btt_fracture(spec, r.breaks, r.seating.step, r.peak_step);
}

TestResult run_compression_test(const JobSpec& job, const RunHooks& hooks) {
  const JobSpec spec = effective_spec(job);
  Simulation sim = make_specimen(spec, hooks.comm);
  RunClock clock(hooks, spec.output.progress_seconds);
  const LoadingSpec& ld = spec.loading;
  const double length = loaded_length(spec);
  const double speed = platen_speed(spec);
  const double t_max = ld.max_strain * length / (2.0 * speed);  // both platens move
  const double transit = wave_transit_time(spec);
  // Speed changes take at least kRampTransits wave transits, or the platens ring the specimen. A
  // given speed ramps over ramp_fraction of the run at most; the auto speed over kRampTransits,
  // the same time whatever the strengths (which keeps the run homogeneous in them).
  const double t_ramp = ld.platen_velocity_m_s
                            ? std::max(ld.ramp_fraction * t_max, kRampTransits * transit)
                            : kRampTransits * transit;
  const std::int64_t max_steps = ld.max_steps.value_or(std::numeric_limits<std::int64_t>::max());
  // Curve rows and VTK frames are spaced by platen closure, so a slowed-down phase is not
  // oversampled.
  const double max_closure = ld.max_strain * length;
  const double curve_spacing = max_closure / static_cast<double>(spec.output.curve_points);
  const double frame_spacing = max_closure / static_cast<double>(spec.output.vtk_frames);
  double next_curve = 0.0, next_frame = frame_spacing;

  Wall& bottom = sim.walls[kBottomPlaten];
  Wall& top = sim.walls[kTopPlaten];
  const double gap0 = top.point.z() - bottom.point.z();

  TestResult r;
  r.test = spec.test;
  r.confining_pressure_pa = spec.loading.confining_pressure_pa;
  count_specimen(sim, r);
  PeakTracker peak{ld.stop_load_fraction,
                   min_failure_breaks(r.bonds, spec.sample.diameter_m / spec.sample.radius_m)};
  // The auto speed holds while a bond-controlled peak is expected. Past that closure a load that
  // still rises is not a strength: the run ends there, or (speed_up_past_window) speeds up.
  const bool auto_speed = !ld.platen_velocity_m_s;
  const bool stop_past_window = auto_speed && !ld.speed_up_past_window;
  SpeedSchedule schedule{speed, ld.slow_factor, t_ramp,
                         stop_past_window ? 0.0 : late_platen_speed(spec)};
  const double late_closure = kBondControlledWindow * bond_failure_strain(spec) * length;
  const double follow_per_m = follow_rate(spec);  // speed per metre of closure; 0 when off
  std::int64_t late_step = -1;
  bool slow_peak = false;
  const auto slow_trigger = static_cast<std::int64_t>(
      std::max(1.0, std::ceil(ld.slow_trigger_broken_fraction * static_cast<double>(r.bonds))));
  r.dt_s = sim.dt;
  // The kinetic / bond energy ratio, sampled at every curve row (a sum over particles and bonds
  // per row, not per step); the result reports the last sample at or before the peak.
  double energy_ratio = 0.0, energy_ratio_at_peak = 0.0;
  bool followed_at_peak = false;  // the follow speed set the platens' speed at the peak
  auto sample_energy = [&] {
    double e[2] = {kinetic_energy(sim.particles), bond_energy(sim.bonds, sim.particles)};
    reduce_sum(sim.domain, e, 2);
    energy_ratio = e[1] > 0.0 ? e[0] / e[1] : 0.0;
  };
  double load = 0.0, closure = 0.0;  // closure counts from the seated state
  double seat_closure = 0.0;
  int frame = 0;
  auto snapshot = [&] { hooks.on_frame(sim, Frame{frame++, sim.step, sim.time, load, closure}); };
  if (hooks.on_frame) snapshot();

  auto progress = [&](double elapsed) {
    // The closure the run ends at unless it fails first.
    const double end_closure =
        stop_past_window ? std::min(max_closure, seat_closure + late_closure) : max_closure;
    double f =
        std::max((seat_closure + closure) / end_closure, double(sim.step) / double(max_steps));
    if (peak.peak_load > 0 && load < peak.peak_load)  // past the peak: how far to the stop load
      f = std::max(f, (peak.peak_load - load) / (peak.peak_load * (1.0 - ld.stop_load_fraction)));
    return Progress{sim.step, std::min(1.0, f), load, peak.peak_load, sim.broken_total, elapsed};
  };

  // The triaxial specimen is confined first. Without pressure there is nothing to ramp in, and
  // the triaxial test is the UCT to the last bit. Loads count from the confined state.
  double base_load = 0.0;
  if (spec.test == TestKind::triaxial && spec.loading.confining_pressure_pa > 0) {
    if (!confine(sim, spec, clock, max_steps, progress))
      r.stop_reason = sim.step >= max_steps ? "max_steps" : "cancelled";
    base_load = 0.5 * (top.reaction.z() - bottom.reaction.z());
  }
  if (r.stop_reason.empty())
    r.stop_reason = seat(sim, spec, clock, max_steps, base_load, t_ramp, r.seating, progress);
  seat_closure = gap0 - (top.point.z() - bottom.point.z());
  r.seating.closure_m = seat_closure;
  peak.start(sim.broken_total);
  load = 0.5 * (top.reaction.z() - bottom.reaction.z());
  // Lateral strain (UCT, triaxial): the mid-height third's radial strain since the seated state,
  // compression positive like the axial strain. Every rank measures at the same curve points (the
  // closure is global); under decomposition a particle that changes rank leaves the fit.
  const bool lateral = spec.test != TestKind::btt && r.stop_reason.empty();
  std::unordered_map<std::int64_t, Vec3> band;  // by id: local indices change at rebuilds
  for (std::size_t k = 0; lateral && k < sim.particles.n_owned; ++k) {
    if (std::abs(sim.particles.pos[k].z()) <= spec.sample.height_m / 6.0)
      band.emplace(sim.particles.id[k], sim.particles.pos[k]);
  }
  auto lateral_strain = [&]() -> std::optional<double> {
    if (!lateral) return std::nullopt;
    const double strain = radial_strain(sim, band);
    return strain == 0.0 ? 0.0 : -strain;  // 0, not -0, at the start
  };
  // Strain gauges over the interior (UCT, triaxial), read at every curve row from the seated
  // state on: the row count is bounded by the closure spacing, so their buffer is reserved once.
  Gauges gauges;
  if (lateral)
    gauges = place_gauges(sim, spec, static_cast<std::size_t>(spec.output.curve_points) + 2);
  auto add_row = [&] {
    r.curve.push_back({sim.step, sim.time, closure, load, sim.broken_total, lateral_strain()});
    if (lateral) read_gauges(sim, gauges, r.curve.size() - 1);
  };
  if (r.stop_reason.empty()) {
    add_row();
    next_curve = curve_spacing;
  }

  // The measured loading, from the seated state at rest: the speed ramps in again.
  double t = 0.0;
  while (r.stop_reason.empty()) {
    if (sim.broken_total >= slow_trigger) schedule.slow_down_from(t);
    if (closure >= late_closure && late_step < 0 && schedule.late_m_s > speed) {
      schedule.speed_up_from(t);
      late_step = sim.step;
    }
    const double scheduled = schedule.speed_at(t + 0.5 * sim.dt);
    const double following = follow_per_m * closure;
    const double v = std::max(scheduled, following);
    bottom.velocity = Vec3(0, 0, v);
    top.velocity = Vec3(0, 0, -v);
    sim.advance();
    t += sim.dt;

    closure = gap0 - (top.point.z() - bottom.point.z()) - seat_closure;
    load = 0.5 * (top.reaction.z() - bottom.reaction.z());
    if (schedule.slow_phase(t) && !slow_peak) {  // track the peak afresh at the slow speed
      slow_peak = true;
      peak.forget(sim.broken_total);
    }
    // A peak only counts once the ramp is over (the tracker keeps it until then).
    const bool failed =
        peak.update(load, closure, sim.step, sim.broken_total) && !schedule.changing(t);
    if (closure >= next_curve) {
      add_row();
      next_curve = closure + curve_spacing;
      sample_energy();
    }
    if (peak.peak_step == sim.step) {
      energy_ratio_at_peak = energy_ratio;
      followed_at_peak = following > scheduled;
    }
    if (hooks.on_frame && closure >= next_frame) {
      snapshot();
      next_frame = closure + frame_spacing;
    }
    clock.maybe_report(progress);

    if (failed)
      r.stop_reason = "post_peak";
    else if (stop_past_window && closure >= late_closure && peak.peak_step == sim.step)
      r.stop_reason = "past_window";  // the load still rises: no bond-controlled peak
    else if (seat_closure + closure >= max_closure)
      r.stop_reason = "max_strain";
    else if (sim.step >= max_steps)
      r.stop_reason = "max_steps";
    else if (sim.stop_global)
      r.stop_reason = "cancelled";
    if (!r.stop_reason.empty()) break;
    sim.stop_local = clock.stop_requested();  // decided together after the next step
  }
  if (r.curve.empty() || r.curve.back().step != sim.step) add_row();
  if (hooks.on_frame) snapshot();
  clock.maybe_report(progress, true);

  r.peak_reached = r.stop_reason == "post_peak";
  r.peak_load_n = r.peak_reached ? peak.peak_load : peak.max_load;
  r.peak_displacement_m = peak.peak_closure;
  r.peak_step = peak.peak_step;
  r.broken_at_peak = peak.broken_at_peak;
  r.loading_rate = LoadingRate{speed,
                               !ld.platen_velocity_m_s,
                               bond_failure_strain(spec),
                               transit,
                               (r.peak_step - r.seating.step) * sim.dt / transit,
                               energy_ratio_at_peak,
                               kQuasiStaticTransits,
                               late_step >= 0 ? schedule.late_m_s : 0.0,
                               late_step >= 0 && r.peak_step >= late_step,
                               std::nullopt,
                               ld.follow_transits,
                               followed_at_peak};
  if (!r.peak_reached) r.no_peak_reason = peak.no_peak_reason(r.stop_reason);
  r.strength_pa = strength_pa(spec, r.peak_load_n);
  if (spec.test != TestKind::btt && r.peak_reached) {
    const double area = axial_area_m2(spec.sample.diameter_m);  // the strength's cross-section
    r.youngs_modulus_pa = prepeak_modulus(r.curve, base_load, r.peak_load_n, area, length);
    const GaugeFit gauge = gauge_fit(gauges.readings, r.curve, base_load, r.peak_load_n, area);
    r.poisson_ratio = gauge.poisson_ratio;
    r.gauge_modulus_pa = gauge.youngs_modulus_pa;
    r.peak_strain = r.peak_displacement_m / length;
  }
  r.steps = sim.step;
  r.broken_bonds = sim.broken_total;
  r.breaks = std::move(sim.breaks);
  tally_breaks(spec, r);
  r.wall_seconds = clock.elapsed_s();
  return r;
}

TestResult run_test(const JobSpec& spec, const RunHooks& hooks) {
  if (spec.test == TestKind::elastic) return run_elastic_test(spec, hooks);
  return spec.loading.rate_study ? run_rate_study(spec, hooks)
                                 : run_with_quasi_static_rerun(spec, hooks);
}

}  // namespace rockcal
