// The twin design (docs/diagnosis.md, "Twins"): the observations a synthetic twin measures for a
// job template, their conditions and roles, and the engine job of each. Deterministic for a
// template, so every twin of one template shares its conditions and differs only in what it hides.
#pragma once

#include <functional>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/spec.hpp"
#include "orchestrator/diagnosis/dataset/dataset.hpp"

namespace rockcal::diagnosis {

// The confining pressures as fractions of the template's UCS at its default bond strengths.
inline constexpr double kLowConfinement = 0.1;
inline constexpr double kHighConfinement = 0.3;
// The platen speed of the fast UCT and the fast disc, as a multiple of the template's.
inline constexpr double kFastSpeedFactor = 4.0;

struct TwinDesign {
  nlohmann::json job_template;  // as given (no "test", no "effects"; "bond" optional)
  JobSpec model;                // the template parsed as a UCT (its sample, speed, default bonds)
  double base_ucs_pa = 0.0;     // UCS of the template's own UCT at its default bond strengths
  double p_low_pa = 0.0;        // kLowConfinement x base UCS, two significant digits
  double p_high_pa = 0.0;       // kHighConfinement x base UCS, two significant digits
  // Model units, every condition stated; value and uncertainty are 0 until measured.
  std::vector<Observation> observations;
};

// The `rockcal twin` default template: an FCC cylinder D = 8, H = 16, R = 1 (117 particles) with
// the seed lab example's two-rate loading, so each run takes about a second.
nlohmann::json demo_twin_template();

// Runs rockcal-dem jobs (full job JSON, with "test") and returns each run's result.json, in order.
// Throws when a run fails.
using RunJobs = std::function<std::vector<nlohmann::json>(const std::vector<nlohmann::json>&)>;

// The template through the engine's own validation for every test the twin runs (no "test" or
// "effects": the twin sets them; "bond" optional), parsed as a UCT. Throws orch::RequestError
// naming the field under "job." as a calibration campaign's errors do.
JobSpec check_twin_template(const nlohmann::json& job_template);

// Checks the template (check_twin_template), runs its base UCT once through `run` for the UCS, and
// lays out the design:
//   calibration: UCT peak load and Young's modulus (D, H); BTT peak load (D, t); triaxial peak
//                load at p_low (D, H); BTT at 4x the platen speed (D, t)
//   held out:    triaxial at p_high (D, H); UCT at H/D = 1 (D, D); BTT at 1.5 D x 1.5 t; UCT at
//                4x the platen speed; the UCT's peak strain (D, H; the base UCT's run)
// Throws orch::RequestError naming "job..." for a bad template.
TwinDesign make_twin_design(const nlohmann::json& job_template, const RunJobs& run);

// The engine job measuring `o` (model units, conditions stated): the template with the
// observation's test, specimen, platen speed and confining pressure, the given bond strengths and
// effects block (omitted when empty). Canonical (parse_job + to_json), so equal runs are equal.
nlohmann::json observation_job(const nlohmann::json& job_template, const Observation& o,
                               double fr0_n, double fs0_n, const nlohmann::json& effects);

// The two-significant-digit rounding of the confining pressures (exposed for tests).
double round_to_two_digits(double x);

}  // namespace rockcal::diagnosis
