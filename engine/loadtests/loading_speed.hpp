// The platen speed a run uses, and how quasi-static its peak was (docs/loading-rate.md).
//
// A fixed platen speed loads a weak rock relatively faster than a strong one: its bonds break at a
// smaller strain, reached in fewer elastic-wave transits, so its peak carries more inertia. The
// "auto" speed follows the bonds' failure strain instead: the platens close by it in
// loading.auto_transits transits. Since that speed is proportional to the strengths, scaling both
// strengths by k scales every displacement, velocity and force of the run by k at the same times:
// the peak load is homogeneous of degree 1 in the strengths (up to the small-strain geometry).
#pragma once

#include "engine/spec.hpp"

namespace rockcal {

// A bond-controlled peak comes within a few bond failure strains (about 5 at F_s0 = F_r0 in the
// UCT). The auto speed holds for this many; past them the platens speed up so that the rest of
// max_strain takes at most kLateTransits wave transits (a damaged specimen can carry the load to
// large strains, and a weak rock's auto speed would take millions of steps to get there). A peak
// after that window may be set by the large-strain geometry rather than by the strengths
// (docs/loading-rate.md measures both cases).
constexpr double kBondControlledWindow = 25.0;
constexpr double kLateTransits = 500.0;

// A run counts as quasi-static when its peak came at least this many elastic-wave transits after
// the seated state. Measured at D/R 20 (docs/loading-rate.md, "The auto speed"): from 80 transits
// on, the peak lay within 5% of the slowest run's with one speed and within 1.5% with two-rate
// loading; at 20 transits, 17-24% above it. (The kinetic / bond energy ratio at the peak is
// reported too, but it fell non-monotonically with the speed and depends on the size.)
constexpr double kQuasiStaticTransits = 80.0;

// The strain at which the first bonds of the lattice fail: the smaller of the tensile and the
// shear failure displacements (F_r0 / K_r, F_s0 / K_s) over the bond length 2R. Effective spec.
double bond_failure_strain(const JobSpec& spec);

// The speed of each platen: loading.platen_velocity, or for "auto" the speed that closes the
// specimen by bond_failure_strain in loading.auto_transits wave transits. Effective spec.
double platen_speed(const JobSpec& spec);

// The speed past the bond-controlled window: for "auto", the faster of the auto speed and the one
// that covers max_strain in kLateTransits transits; a given speed stays as it is.
double late_platen_speed(const JobSpec& spec);

// The follow speed (loading.follow_transits n, "auto" only) per metre of closure: times the closure
// since seating, the speed that closes the specimen by it in n wave transits; 0 when off. The
// platens move at the larger of that and the scheduled speed, so the closure grows at most
// exponentially with time constant n transits once it passes the auto speed's reach.
//
// Why: the auto speed follows the first bond failure, but where F_s0 exceeds F_r0 the peak comes
// 7-25 failure strains later (the shear bonds and friction carry the load while tensile bonds
// break), so such runs took 3-7x the transits the quasi-static measure asks (docs/loading-rate.md).
// At the follow speed the loading's relative rate (closure rate over closure) never exceeds 1 / n
// per transit: the peak is loaded as slowly, relative to its own strain, as a linear load that
// reaches it in n transits, wherever it comes, and a run that took n ln(c_p / c_0) transits past
// c_0 took (c_p - c_0) / rate before. Since the closure scales with the strengths, so does the
// speed: the run stays homogeneous of degree 1 in them.
//
// The UCT and triaxial only: a disc's platen closure is mostly the indentation of its two
// contacts, not the bonds' strain, so its relative rate does not say how fast the bonds are loaded
// (measured at D/R 20, (25, 45) and (40, 40), three seeds: followed at 100 transits the BTT peaks
// came 4-5% above a 4x slower run's, against 1-2% without; docs/loading-rate.md). The BTT
// ignores it, as the elastic test ignores the rerun; its runs are cheap either way.
double follow_rate(const JobSpec& spec);

}  // namespace rockcal
