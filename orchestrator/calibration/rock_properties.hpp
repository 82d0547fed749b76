// The rock a calibration's answer describes, in the units the lab reports: UCS and BTS from the
// predicted peak loads at the estimate (each through its own specimen's strength definition), and
// the Young's modulus and Poisson's ratio the stiffness stage's elastic test or else the check runs
// at the estimate measured, beside the lab's own values where the request gave them. What a PFC
// user reads off a material test.
#pragma once

#include <nlohmann/json.hpp>

#include "orchestrator/calibration/report.hpp"

namespace rockcal::calibration {

// {"units": "lab" | "model", "ucs_pa": {"value", "interval"}, "bts_pa": {...},
//  "youngs_modulus_pa": {"value", "runs", "measure", "uct", "lab"}, "poisson_ratio": {...}};
// null without a posterior. "measure" is "elastic" (the stiffness stage's confirming elastic test,
// when E or nu was a target) or "uct" (the check runs: E the pre-peak slope); "uct" is the check
// runs' mean either way. A modulus or ratio nothing measured is null.
nlohmann::json rock_properties_json(const CalibrationReport& r, const CalibrationCampaign& c);

}  // namespace rockcal::calibration
