// Load <-> strength of the two specimens: UCS = F / A of the cylinder, Brazilian
// BTS = 2 P / (pi D t) of the disc. Used for strength targets and for reporting strengths.
#pragma once

namespace rockcal::calibration {

struct Specimen {
  double diameter_m;
  double height_m;     // UCT cylinder
  double thickness_m;  // BTT disc
};

double uct_strength_pa(double load_n, const Specimen& specimen);
double uct_load_n(double strength_pa, const Specimen& specimen);
double btt_strength_pa(double load_n, const Specimen& specimen);
double btt_load_n(double strength_pa, const Specimen& specimen);

}  // namespace rockcal::calibration
