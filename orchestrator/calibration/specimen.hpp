// Load <-> strength of the two specimens by the engine's definitions
// (engine/loadtests/strength.hpp): UCS = F / A of the cylinder, BTS = k 2P / (pi D t) of the disc.
// Used for strength targets and for reporting strengths.
#pragma once

#include <nlohmann/json.hpp>

namespace rockcal::calibration {

struct Specimen {
  double diameter_m;
  double height_m;     // UCT cylinder
  double thickness_m;  // BTT disc
  // k of the disc's BTS: the model's from its Brazilian set-up (btt_strength_factor); a lab disc's
  // is the ISRM test's, 1.
  double btt_factor = 1.0;
};

double uct_strength_pa(double load_n, const Specimen& specimen);
double uct_load_n(double strength_pa, const Specimen& specimen);
double btt_strength_pa(double load_n, const Specimen& specimen);
double btt_load_n(double strength_pa, const Specimen& specimen);

// {"uct": {"name", "formula", "factor"}, "btt": {...}}: how the strengths beside the loads were
// computed on this specimen.
nlohmann::json strength_definitions_json(const Specimen& specimen);

}  // namespace rockcal::calibration
