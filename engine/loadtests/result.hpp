// What a test run produces: the reduced figures and the curve a plot needs.
#pragma once

#include <mpi.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/bonds.hpp"
#include "engine/loadtests/brazilian.hpp"
#include "engine/spec.hpp"

namespace rockcal {

struct Simulation;

struct CurvePoint {
  std::int64_t step;
  double time_s;
  double displacement_m;  // platen closure
  double load_n;
  std::int64_t broken_bonds;
  // UCT and triaxial, from the seated state on: the mid-height third's lateral strain,
  // compression positive like the axial strain (expansion negative).
  std::optional<double> lateral_strain = std::nullopt;
};

// Peak load against platen speed, extrapolated to zero speed (rate study).
struct RateStudy {
  std::vector<double> speeds_m_s, peaks_n, wall_seconds;
  double extrapolated_peak_n = 0.0;
  double rate_error = 0.0;  // |slowest peak - extrapolated| / extrapolated
  bool converged = false;   // peaks converged geometrically; otherwise the error is a bound guess
};

// The first run of a test that ran again slower (loadtests/quasi_static_rerun.hpp).
struct QuasiStaticRerun {
  double first_peak_transits = 0.0;
  double first_peak_load_n = 0.0;
  double auto_transits = 0.0;  // the rerun's
};

// How fast the test loaded and how quasi-static its peak was (loadtests/loading_speed.hpp).
struct LoadingRate {
  double platen_velocity_m_s = 0.0;  // the speed used (each platen)
  bool automatic = false;            // loading.platen_velocity "auto"
  double bond_failure_strain = 0.0;
  double wave_transit_s = 0.0;        // elastic-wave transit time along the loaded length
  double peak_transits = 0.0;         // from the seated state to the peak, in wave transits
  double kinetic_energy_ratio = 0.0;  // kinetic / bond energy at the peak (its last curve row)
  double min_transits = 0.0;          // quasi-static when peak_transits >= min_transits
  double late_velocity_m_s = 0.0;     // auto: the speed past the bond-controlled window, if reached
  bool late_peak = false;             // the peak came after that window (and at the faster speed)
  std::optional<QuasiStaticRerun> rerun;  // this run followed one that came too fast
  double follow_transits = 0.0;           // loading.follow_transits (0: off)
  bool followed = false;                  // the follow speed set the speed at the peak
  bool quasi_static() const { return peak_transits >= min_transits; }
};

// The state the measurement starts from (loadtests/seating.hpp).
struct Seating {
  double load_n = 0.0;            // seating load the platens closed to
  double closure_m = 0.0;         // platen closure when it was reached (the curve's zero)
  std::int64_t step = 0;          // first step of the measured loading
  std::int64_t broken_bonds = 0;  // broken while seating (a rough end's grains)
};

struct TestResult {
  TestKind test = TestKind::uct;
  // A peak with failure (loadtests/peak.hpp). When false, peak_load_n is only the largest load
  // seen and no_peak_reason says why: not a strength.
  bool peak_reached = false;
  std::string no_peak_reason;
  double peak_load_n = 0.0;
  double strength_pa = 0.0;                 // loadtests/strength.hpp; elastic: 0
  double confining_pressure_pa = 0.0;       // triaxial: the lateral pressure; others 0
  std::optional<double> youngs_modulus_pa;  // UCT pre-peak slope, or elastic test
  // Elastic test, or UCT / triaxial with a peak: the interior's, over the modulus's window from
  // strain gauges (loadtests/gauges.hpp).
  std::optional<double> poisson_ratio;
  // UCT / triaxial with a peak: the platen stress over the interior's axial strain (the gauges'),
  // over the same window: E as a lab's gauges measure it, without the specimen's ends.
  std::optional<double> gauge_modulus_pa;
  double peak_displacement_m = 0.0;  // platen closure from the seated state
  // UCT / triaxial with a peak: the axial strain at peak, closure over the loaded length. Moves
  // with packing, rate, compression coupling and interaction range where the peak load barely
  // does once the strengths are re-fitted (docs/effects.md, "Signatures").
  std::optional<double> peak_strain;
  std::int64_t peak_step = 0;
  std::int64_t broken_at_peak = 0;  // damage when the peak was reached
  std::int64_t particles = 0, bonds = 0, broken_bonds = 0;
  std::int64_t floaters_removed = 0;  // particles with too few bonds, dropped before bonding
  Seating seating;
  std::optional<BttFracture> btt_fracture;  // BTT: where the disc broke first
  std::array<std::int64_t, 4> broken_by{};  // by BreakMode
  std::int64_t steps = 0;
  double dt_s = 0.0;
  double wall_seconds = 0.0;
  std::string stop_reason;
  std::vector<CurvePoint> curve;
  std::vector<BreakEvent> breaks;
  std::optional<RateStudy> rate_study;
  std::optional<LoadingRate> loading_rate;  // loading tests (not the elastic test)
};

struct Progress {
  std::int64_t step;
  double fraction;  // 0..1, an estimate
  double load_n, peak_load_n;
  std::int64_t broken_bonds;
  double elapsed_s;
};

// One VTK snapshot: its number and the loading state it shows.
struct Frame {
  int index = 0;
  std::int64_t step = 0;
  double time_s = 0.0;
  double load_n = 0.0;
  double displacement_m = 0.0;  // platen closure from the seated state
};

// Hooks a run calls; all optional. `stop` is polled each step (set by a signal handler). With a
// communicator of several ranks the run is decomposed; progress and frames are then per rank.
struct RunHooks {
  MPI_Comm comm = MPI_COMM_NULL;
  std::function<void(const Progress&)> on_progress;
  std::function<void(const Simulation&, const Frame&)> on_frame;  // VTK snapshots
  const std::atomic<bool>* stop = nullptr;
};

}  // namespace rockcal
