// The strength a loading test reports from its peak load: one definition for the engine's result,
// the service's results and the calibration report.
//   UCS (UCT) and sigma_1 (triaxial, the axial stress at the peak) = F / A, A = pi D^2 / 4;
//   BTS = k 2P / (pi D t), k the Brazilian set-up's factor (btt_strength_factor: 1 for a full
//   disc, about 0.913 for the default flattened disc of 2 alpha = 30 degrees).
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/spec.hpp"

namespace rockcal {

struct StrengthDefinition {
  std::string name;     // "UCS", "sigma_1" or "BTS"
  std::string formula;  // "F / A" or "k 2P / (pi D t)"
  double factor = 1.0;  // k (1 for F / A)
};

StrengthDefinition axial_strength_definition(TestKind test);  // uct or triaxial
StrengthDefinition bts_definition(double factor);
// The definition a job's strength follows; none for the elastic test (no strength).
std::optional<StrengthDefinition> strength_definition(const JobSpec& spec);

// {"name", "formula", "factor"}.
nlohmann::json to_json(const StrengthDefinition& d);

double axial_area_m2(double diameter_m);  // pi D^2 / 4
double axial_strength_pa(double load_n, double diameter_m);
double axial_load_n(double strength_pa, double diameter_m);
double bts_pa(double load_n, double diameter_m, double thickness_m, double factor);
double bts_load_n(double strength_pa, double diameter_m, double thickness_m, double factor);

// A loading job's strength at `peak_load_n` by its definition (0 for the elastic test).
double strength_pa(const JobSpec& spec, double peak_load_n);

}  // namespace rockcal
