// The Brazilian test's set-up and reduction: the disc for each loading geometry, its strength
// formula, and where the disc broke first (the test is valid only when it splits from its centre).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/bonds.hpp"
#include "engine/packing/fcc.hpp"
#include "engine/spec.hpp"

namespace rockcal {

// The specimen shape: the full disc, or (flattened) the disc with flats at |z| = D/2 cos(alpha).
Disc btt_disc(const JobSpec& spec);

// Wang et al. (2004, IJRMMS 41:245) for a flattened disc of loading angle 2 alpha:
// sigma_t = k 2P / (pi D t), k = (2 cos^3 a + cos a + sin a / a)^2 / (8 (cos a + sin a / a)) a /
// sin a. 1 for the full disc (flat platens, curved jaws: the ISRM formula 2P / (pi D t)). The
// strength itself: loadtests/strength.hpp.
double btt_strength_factor(const LoadingSpec& loading);

// ISRM jaws are wider than the contact they make (about 10 degrees of arc at failure); a face of
// +-30 degrees about the loading axis, seen from the jaw's axis, never runs out of jaw.
constexpr double kJawHalfAngleRad = 30.0 * 3.14159265358979323846 / 180.0;

// Where the disc broke first. Grains under the loading surfaces break early whatever the set-up
// (a jaw or a flat's edge bears on a few surface particles); the question for the test's validity
// is where the splitting crack starts: the first breaks inside the disc, more than one particle
// diameter in from the rim. They should sit near the centre (r / R small), and the damage up to the
// end along the loaded diameter (the z axis).
constexpr int kFirstBreaks = 20;
constexpr double kLoadedBandHalfWidth = 0.2;  // of the radius: |x| / R below this is "on" it
constexpr double kCentreSplitRadius = 0.5;    // median r / R of the first interior breaks

struct BttFracture {
  std::int64_t rim_breaks_before_peak = 0;  // within a particle diameter of the rim
  std::int64_t first_count = 0;             // interior breaks the origin is judged on
  double first_median_r_over_R = 0.0;       // distance from the centre over the disc radius
  double first_max_r_over_R = 0.0;
  // Of all breaks after seating: the share within kLoadedBandHalfWidth R of the loaded diameter
  // (a uniform spread over the disc gives 0.25).
  double loaded_band_fraction = 0.0;
  bool centre_split = false;  // first_median_r_over_R <= kCentreSplitRadius
};

// `breaks` sorted by step, from every rank; those before `from_step` (seating) are left out.
BttFracture btt_fracture(const JobSpec& spec, const std::vector<BreakEvent>& breaks,
                         std::int64_t from_step, std::int64_t peak_step);

}  // namespace rockcal
