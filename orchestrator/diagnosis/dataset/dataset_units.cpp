// Lab -> model units for dataset observations (eq. 4, engine/units.hpp), the way a calibration
// campaign maps its lab targets.
#include "orchestrator/calibration/lab_case.hpp"
#include "orchestrator/diagnosis/dataset/dataset.hpp"

namespace rockcal::diagnosis {

double model_per_lab(Observable o, const Scaling& scaling) {
  // A peak load is a force; a strength and a modulus are stresses (force / length^2); a strain
  // has no unit.
  switch (o) {
    case Observable::peak_load:
      return scaling.force;
    case Observable::strength:
    case Observable::youngs_modulus:
      return scaling.stress;
    case Observable::peak_strain:
      return 1.0;
  }
  return 1.0;
}

Observation to_model_units(const Observation& o, const Dataset& d) {
  if (!d.scaling) return o;
  const Scaling& s = *d.scaling;
  const calibration::Specimen& lab = d.lab->specimen;
  Observation m = o;
  const double factor = model_per_lab(o.observable, s);
  m.value = o.value * factor;
  m.uncertainty = o.uncertainty * factor;
  Conditions& c = m.conditions;
  // Absent dimensions are the lab specimen's; after mapping they are stated, because the job
  // template's own sample is no stand-in for a lab specimen.
  c.diameter_m = s.length_to_model(o.conditions.diameter_m.value_or(lab.diameter_m));
  if (o.test == TestKind::btt) {
    c.thickness_m = s.length_to_model(o.conditions.thickness_m.value_or(lab.thickness_m));
  } else {
    c.height_m = s.length_to_model(o.conditions.height_m.value_or(lab.height_m));
  }
  c.confining_pressure_pa = s.stress_to_model(o.conditions.confining_pressure_pa);
  if (o.conditions.loading_rate_m_s) {
    c.loading_rate_m_s = s.velocity_to_model(*o.conditions.loading_rate_m_s);
  }
  return m;
}

Dataset in_model_units(const Dataset& d) {
  Dataset m = d;
  for (Observation& o : m.observations) o = to_model_units(o, d);
  m.lab.reset();
  m.scaling.reset();
  return m;
}

void check_model_scale(const Dataset& d, const JobSpec& job_template) {
  if (!d.lab) return;
  calibration::check_model_scale(d.lab->model, calibration::model_choice_of(job_template),
                                 "model_scale");
}

}  // namespace rockcal::diagnosis
