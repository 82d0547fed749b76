#include "orchestrator/calibration/specimen.hpp"

#include "engine/loadtests/strength.hpp"

namespace rockcal::calibration {

double uct_strength_pa(double load_n, const Specimen& s) {
  return axial_strength_pa(load_n, s.diameter_m);
}
double uct_load_n(double strength_pa, const Specimen& s) {
  return axial_load_n(strength_pa, s.diameter_m);
}
double btt_strength_pa(double load_n, const Specimen& s) {
  return bts_pa(load_n, s.diameter_m, s.thickness_m, s.btt_factor);
}
double btt_load_n(double strength_pa, const Specimen& s) {
  return bts_load_n(strength_pa, s.diameter_m, s.thickness_m, s.btt_factor);
}

nlohmann::json strength_definitions_json(const Specimen& s) {
  return {{"uct", to_json(axial_strength_definition(TestKind::uct))},
          {"btt", to_json(bts_definition(s.btt_factor))}};
}

}  // namespace rockcal::calibration
