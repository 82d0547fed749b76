// Calibration targets and their mapping to the model's units. Targets are peak loads (N) or
// strengths (Pa), in model units or in lab units; lab values go through eq. 4 (make_scaling).
#pragma once

#include <optional>

#include "engine/units.hpp"
#include "orchestrator/calibration/evaluator.hpp"
#include "orchestrator/calibration/specimen.hpp"

namespace rockcal::calibration {

enum class TargetQuantity { peak_load, strength };

// One target as the user gave it: N for a peak load, Pa for a strength, in the campaign's units.
struct TargetValue {
  TargetQuantity quantity;
  double value;
};

// The lab side of eq. 4 plus the model's chosen scale (K_r2, R2, rho2 and optionally x2/x1).
struct LabCase {
  Specimen specimen;
  LabMaterial material;
  ModelChoice model;
  std::optional<double> length_ratio;
};

// The specimen's elastic constants the stiffness stage matches (stiffness.hpp), where the request
// gives them: E in the targets' units (Pa, lab or model), nu without a unit.
struct ElasticTargets {
  std::optional<double> youngs_modulus_pa;
  std::optional<double> poisson_ratio;
  bool any() const { return youngs_modulus_pa || poisson_ratio; }
};

struct Targets {
  TargetValue uct;
  TargetValue btt;
  std::optional<LabCase> lab;      // set when the values are in lab units
  std::optional<Scaling> scaling;  // make_scaling(lab) when lab is set
  PeakLoads model_loads_n;         // what the search matches, model units
  ElasticTargets elastic;          // E and nu, when the request asks for them
};

// The target Young's modulus in model units (a lab modulus times eq. 4's stress scale), if any.
std::optional<double> model_youngs_modulus_pa(const Targets& targets);

// Resolves the model-unit peak loads. Strengths become loads on their own specimen (the lab's
// for lab units, the model sample for model units); lab loads map to the model by the force scale,
// the way the seed paper mapped 311 kN to 161.85 kN.
Targets resolve_targets(TargetValue uct, TargetValue btt, const Specimen& model_specimen,
                        std::optional<LabCase> lab);

// Model -> lab for the report.
PeakLoads loads_to_lab(const PeakLoads& model_n, const Scaling& scaling);
BondPoint bonds_to_lab(const BondPoint& model_n, const Scaling& scaling);

}  // namespace rockcal::calibration
