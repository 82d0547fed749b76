#include "engine/loadtests/strength.hpp"

#include <cmath>

#include "engine/loadtests/brazilian.hpp"

namespace rockcal {

namespace {
// P = BTS (pi D t) / (2 k): the "area" that turns the Brazilian load into the tensile strength.
double btt_area_m2(double diameter_m, double thickness_m, double factor) {
  return 0.5 * M_PI * diameter_m * thickness_m / factor;
}
}  // namespace

StrengthDefinition axial_strength_definition(TestKind test) {
  return {test == TestKind::triaxial ? "sigma_1" : "UCS", "F / A", 1.0};
}

StrengthDefinition bts_definition(double factor) {
  return {"BTS", "k 2P / (pi D t)", factor};
}

std::optional<StrengthDefinition> strength_definition(const JobSpec& spec) {
  switch (spec.test) {
    case TestKind::uct:
    case TestKind::triaxial:
      return axial_strength_definition(spec.test);
    case TestKind::btt:
      return bts_definition(btt_strength_factor(spec.loading));
    case TestKind::elastic:
      break;
  }
  return std::nullopt;
}

nlohmann::json to_json(const StrengthDefinition& d) {
  return {{"name", d.name}, {"formula", d.formula}, {"factor", d.factor}};
}

double axial_area_m2(double diameter_m) {
  return 0.25 * M_PI * diameter_m * diameter_m;
}
double axial_strength_pa(double load_n, double diameter_m) {
  return load_n / axial_area_m2(diameter_m);
}
double axial_load_n(double strength_pa, double diameter_m) {
  return strength_pa * axial_area_m2(diameter_m);
}
double bts_pa(double load_n, double diameter_m, double thickness_m, double factor) {
  return load_n / btt_area_m2(diameter_m, thickness_m, factor);
}
double bts_load_n(double strength_pa, double diameter_m, double thickness_m, double factor) {
  return strength_pa * btt_area_m2(diameter_m, thickness_m, factor);
}

double strength_pa(const JobSpec& spec, double peak_load_n) {
  const double d = spec.sample.diameter_m;
  switch (spec.test) {
    case TestKind::uct:
    case TestKind::triaxial:
      return axial_strength_pa(peak_load_n, d);
    case TestKind::btt:
      return bts_pa(peak_load_n, d, spec.sample.btt_thickness(), btt_strength_factor(spec.loading));
    case TestKind::elastic:
      break;
  }
  return 0.0;
}

}  // namespace rockcal
