#include "orchestrator/calibration/specimen.hpp"

#include <cmath>

namespace rockcal::calibration {
namespace {

double uct_area_m2(const Specimen& s) {
  return M_PI * 0.25 * s.diameter_m * s.diameter_m;
}
// P = BTS * (pi D t / 2): the "area" that turns the Brazilian load into the tensile strength.
double btt_area_m2(const Specimen& s) {
  return 0.5 * M_PI * s.diameter_m * s.thickness_m;
}

}  // namespace

double uct_strength_pa(double load_n, const Specimen& s) {
  return load_n / uct_area_m2(s);
}
double uct_load_n(double strength_pa, const Specimen& s) {
  return strength_pa * uct_area_m2(s);
}
double btt_strength_pa(double load_n, const Specimen& s) {
  return load_n / btt_area_m2(s);
}
double btt_load_n(double strength_pa, const Specimen& s) {
  return strength_pa * btt_area_m2(s);
}

}  // namespace rockcal::calibration
