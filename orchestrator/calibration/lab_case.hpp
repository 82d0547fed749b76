// The lab side of lab-unit values (eq. 4): the "lab" block (specimen and material) and the
// "model_scale" block. Shared by a calibration campaign's targets and a lab dataset, so both read
// and check them the same way.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/spec.hpp"
#include "orchestrator/calibration/targets.hpp"
#include "orchestrator/json_fields.hpp"

namespace rockcal::calibration {

// The model's scale of a job: its K_r (given, or from E by eq. 3), R and rho.
ModelChoice model_choice_of(const JobSpec& model);

// Reads `parent`'s "lab" (required) and "model_scale". With `job_model` (a campaign's template),
// model_scale may restate K_r, R, rho and must agree; without one (a dataset stands alone),
// model_scale is required and gives all three. Either way it may add "length_ratio" (x2/x1).
LabCase parse_lab_case(orch::JsonFields& parent, const std::optional<ModelChoice>& job_model);

// Throws orch::RequestError naming `path`.kr / .radius / .density when the stated scale differs
// from the job template's (relative 1e-9).
void check_model_scale(const ModelChoice& stated, const ModelChoice& job, const std::string& path);

// {"lab": {...}, "model_scale": {...}}, as parse_lab_case reads them back.
nlohmann::json lab_case_json(const LabCase& lab);

}  // namespace rockcal::calibration
