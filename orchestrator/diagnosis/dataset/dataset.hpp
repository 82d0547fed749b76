// A lab dataset: the observations a diagnosis calibrates on and predicts. JSON or CSV; values in
// model units, or in lab units together with the lab case that maps them (eq. 4).
// The format is documented in docs/diagnosis.md ("Lab dataset").
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/spec.hpp"
#include "orchestrator/calibration/targets.hpp"
#include "orchestrator/request_error.hpp"

namespace rockcal::diagnosis {

// An invalid dataset; `field` is the path of the offending key ("observations[3].uncertainty").
// The calibration's error type, because the lab block is parsed by the calibration's own code.

// peak_strain: the axial strain at the peak of a UCT or triaxial test (dimensionless).
enum class Observable { peak_load, strength, youngs_modulus, peak_strain };
// Who made the numbers decides which numerical errors separate them from the model's runs
// (budget.hpp, error_terms): a lab or a finer model differ from the model by its resolution and
// its loading speed; a twin made by the same model at the same resolution and speed differs only
// by the draws of its specimen.
enum class Origin { lab, same_resolution_model, finer_model };
enum class Role { calibration, held_out };

// The conditions of one lab test, SI units of the dataset's unit system. Absent = the diagnosis
// job template's value (model units) or the lab case's specimen (lab units).
struct Conditions {
  std::optional<double> diameter_m;
  std::optional<double> height_m;          // UCT / triaxial cylinder
  std::optional<double> thickness_m;       // BTT disc
  double confining_pressure_pa = 0.0;      // triaxial (> 0); 0 for uct / btt
  std::optional<double> loading_rate_m_s;  // platen speed
};

struct Observation {
  std::string id;  // unique within the dataset ("uct-1", "tri-20MPa-a")
  TestKind test;   // uct, btt or triaxial
  Conditions conditions;
  Observable observable;
  double value;        // N (peak_load) or Pa (strength, youngs_modulus), dataset units
  double uncertainty;  // one standard deviation, same unit as value; > 0
  Role role;
};

struct Dataset {
  std::string name;
  std::string note;             // free text: assumptions (e.g. how the uncertainty was chosen)
  std::string source;           // free text: where the numbers come from
  Origin origin = Origin::lab;  // "origin"; a dataset that does not say is treated as lab data
  std::vector<Observation> observations;
  // Set when the values are in lab units: the lab specimen/material and the model's scale, the
  // same block a calibration campaign's "targets" carries ("lab" + "model_scale").
  std::optional<calibration::LabCase> lab;
  std::optional<Scaling> scaling;
};

// Strict parsing: unknown fields, NaN, non-positive values or uncertainties, unknown tests or
// observables, duplicate ids, a dataset without calibration observations: orch::RequestError naming
// the field ("observations[3].uncertainty").
Dataset parse_dataset_json(const nlohmann::json& j);
// One observation of such a dataset, its fields named under `path` ("observations[3]").
Observation parse_observation(const nlohmann::json& j, const std::string& path);
Dataset parse_dataset_csv(const std::string& text);  // header row + one observation per row
nlohmann::json to_json(const Dataset& d);
// The CSV form; throws std::invalid_argument for text a CSV cell or comment line cannot hold
// (a comma in an id, a line break in the note).
std::string to_csv(const Dataset& d);

// By extension: ".csv" is CSV, anything else JSON. Errors name the file.
Dataset read_dataset_file(const std::filesystem::path& file);
void write_dataset_file(const Dataset& d, const std::filesystem::path& file);

const char* to_string(Observable o);
const char* to_string(Role r);
const char* to_string(Origin o);
bool is_triaxial(TestKind test);

// --- Lab -> model units (eq. 4) ---

// model / lab factor of an observable's unit: the force scale for peak loads, the stress scale
// for strengths and moduli.
double model_per_lab(Observable o, const Scaling& scaling);

// One observation in model units: value and uncertainty by model_per_lab, lengths by the length
// scale, confining pressure by the stress scale, loading rate by the velocity scale. A lab
// dataset's absent specimen dimensions become the lab specimen's (mapped); the loading rate stays
// absent (the job template's). Identity for a model-unit dataset.
Observation to_model_units(const Observation& o, const Dataset& d);

// The whole dataset in model units (lab and scaling dropped: the values are no longer lab values).
Dataset in_model_units(const Dataset& d);

// A lab dataset's model_scale must be the job template's own K_r, R and rho (as for a calibration
// campaign); throws orch::RequestError ("model_scale.kr") otherwise. No-op for a model-unit
// dataset.
void check_model_scale(const Dataset& d, const JobSpec& job_template);

// The job template's platen speed, which a condition without a loading rate runs at. The
// diagnosis sets speeds itself (the lab's loading rates, the error budget's half speed), so it
// needs a number: throws orch::RequestError ("job.loading.platen_velocity") for "auto".
double template_platen_speed(const JobSpec& model_template);

}  // namespace rockcal::diagnosis
