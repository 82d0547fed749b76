// Seating, as a lab does it: the platens close on the specimen until a small load holds it, the
// specimen settles, and the measurement (displacement, modulus, peak) starts from that state, not
// from the first touch of a surface grain.
#pragma once

#include "engine/spec.hpp"

namespace rockcal {

// The automatic seating load: this fraction of the job's bond tensile strength F_r0 for every
// (2R)^2 of the loaded section (the cylinder's cross-section for the UCT and triaxial tests, D t
// for the BTT). A specimen carries several F_r0 per (2R)^2 at failure, so the seat stays a small
// fraction of any peak the bonds allow (docs/specimens.md gives it against measured peaks).
constexpr double kSeatingFraction = 0.01;
// After seating the platens stand still for this many elastic-wave transits while damping settles
// the specimen.
constexpr double kSeatingHoldTransits = 1.0;

// loading.seating_load, or the automatic value (effective spec: the bond strength a run uses).
double seating_load(const JobSpec& spec);

}  // namespace rockcal
