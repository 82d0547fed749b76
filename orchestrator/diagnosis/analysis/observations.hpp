// The dataset's observations as the diagnosis uses them: in model units, each with the conditions
// of the run that measures it resolved against the job template, and the lab uncertainty as a
// relative standard deviation (every residual is ln(sim/lab), so u/value is its scale).
#pragma once

#include <compare>
#include <string>
#include <vector>

#include "engine/spec.hpp"
#include "orchestrator/diagnosis/dataset/dataset.hpp"

namespace rockcal::diagnosis {

// Everything that makes two observations need different engine runs. Observations with equal
// conditions (the UCT's peak load and its Young's modulus) are read off one run.
struct RunConditions {
  TestKind test = TestKind::uct;
  double diameter_m = 0.0;
  double height_m = 0.0;
  double thickness_m = 0.0;
  double confining_pressure_pa = 0.0;
  double platen_velocity_m_s = 0.0;
  auto operator<=>(const RunConditions&) const = default;
};

struct Target {
  std::string id;
  Observable observable = Observable::peak_load;
  Role role = Role::calibration;
  RunConditions conditions;
  double value = 0.0;  // model units: N (peak_load) or Pa (strength, youngs_modulus)
  double sigma = 0.0;  // uncertainty / value: the standard deviation of ln(value)
};

// Lab units map to model units by eq. 4 first (in_model_units: absent sizes become the lab
// specimen's); then every condition still absent takes the template's value: its sample, its
// platen speed, and for a disc its explicit thickness or else half the disc's own diameter (the
// engine's default). Throws orch::RequestError ("model_scale.kr") when a lab dataset's model scale
// is not the template's.
std::vector<Target> model_targets(const Dataset& dataset, const JobSpec& model_template);

// How many targets have this role.
std::size_t count_role(const std::vector<Target>& targets, Role role);

}  // namespace rockcal::diagnosis
