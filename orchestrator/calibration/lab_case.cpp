#include "orchestrator/calibration/lab_case.hpp"

#include <cmath>

#include "orchestrator/request_error.hpp"

namespace rockcal::calibration {
namespace {

using nlohmann::json;

Specimen parse_lab_specimen(orch::JsonFields& lab) {
  orch::JsonFields s(lab.require("specimen"), lab.path_of("specimen"));
  Specimen specimen{s.required_positive("diameter"), s.required_positive("height"), 0.0};
  // A Brazilian disc of t = D/2 unless stated (examples/datasets/seed_paper/README.md; ISRM
  // proportion).
  specimen.thickness_m = s.positive("thickness").value_or(0.5 * specimen.diameter_m);
  s.reject_unknown();
  return specimen;
}

LabMaterial parse_lab_material(orch::JsonFields& lab) {
  orch::JsonFields m(lab.require("material"), lab.path_of("material"));
  LabMaterial material{m.required_positive("youngs_modulus"), 0.0, m.required_positive("density"),
                       m.required_positive("grain_radius")};
  const auto nu = m.number("nu");
  if (!nu) throw orch::RequestError(m.path_of("nu"), "is required");
  if (!(*nu > -1.0 && *nu < 0.5)) throw orch::RequestError(m.path_of("nu"), "must be in (-1, 0.5)");
  material.nu = *nu;
  m.reject_unknown();
  return material;
}

void agree(const std::string& field, std::optional<double> stated, double from_job,
           const std::string& job_field) {
  if (stated && std::abs(*stated - from_job) > 1e-9 * from_job) {
    throw orch::RequestError(field, "differs from the job template's " + job_field);
  }
}

}  // namespace

ModelChoice model_choice_of(const JobSpec& model) {
  const double kr = model.material.kr_n_m.value_or(kr_from_youngs_modulus(
      model.material.youngs_modulus_pa.value_or(0.0), model.material.nu, model.sample.radius_m));
  return {kr, model.sample.radius_m, model.material.density_kg_m3};
}

void check_model_scale(const ModelChoice& stated, const ModelChoice& job, const std::string& path) {
  agree(path + ".kr", stated.kr_n_m, job.kr_n_m, "material.kr");
  agree(path + ".radius", stated.radius_m, job.radius_m, "sample.radius");
  agree(path + ".density", stated.density_kg_m3, job.density_kg_m3, "material.density");
}

LabCase parse_lab_case(orch::JsonFields& parent, const std::optional<ModelChoice>& job_model) {
  orch::JsonFields lab(parent.require("lab"), parent.path_of("lab"));
  LabCase c{parse_lab_specimen(lab), parse_lab_material(lab), {}, std::nullopt};
  lab.reject_unknown();
  // The model's scale is the job template's own K_r, R and rho when there is a template; the
  // block may restate them (as the paper does) but must agree.
  const json* v = job_model ? parent.get("model_scale") : &parent.require("model_scale");
  if (job_model) c.model = *job_model;
  if (!v) return c;
  orch::JsonFields s(*v, parent.path_of("model_scale"));
  const auto kr = s.positive("kr");
  const auto radius = s.positive("radius");
  const auto density = s.positive("density");
  if (job_model) {
    agree(s.path_of("kr"), kr, job_model->kr_n_m, "material.kr");
    agree(s.path_of("radius"), radius, job_model->radius_m, "sample.radius");
    agree(s.path_of("density"), density, job_model->density_kg_m3, "material.density");
  } else {
    for (const auto& [key, value] : {std::pair{"kr", kr}, {"radius", radius}, {"density", density}})
      if (!value) throw orch::RequestError(s.path_of(key), "is required");
    c.model = {*kr, *radius, *density};
  }
  c.length_ratio = s.positive("length_ratio");
  s.reject_unknown();
  return c;
}

json lab_case_json(const LabCase& lab) {
  json scale = {{"kr", lab.model.kr_n_m},
                {"radius", lab.model.radius_m},
                {"density", lab.model.density_kg_m3}};
  if (lab.length_ratio) scale["length_ratio"] = *lab.length_ratio;
  return {{"lab",
           {{"specimen",
             {{"diameter", lab.specimen.diameter_m},
              {"height", lab.specimen.height_m},
              {"thickness", lab.specimen.thickness_m}}},
            {"material",
             {{"youngs_modulus", lab.material.youngs_modulus_pa},
              {"nu", lab.material.nu},
              {"density", lab.material.density_kg_m3},
              {"grain_radius", lab.material.grain_radius_m}}}}},
          {"model_scale", scale}};
}

}  // namespace rockcal::calibration
