#include "orchestrator/diagnosis/twin/twin_design.hpp"

#include <cmath>

namespace rockcal::diagnosis {

// max_strain 0.2: with platen friction 0.5 the D = 8 triaxial at p_high peaks at 0.166 strain; at
// 0.1 the runs ended before the peak (a run without a peak fails).
nlohmann::json demo_twin_template() {
  return nlohmann::json::parse(R"({
    "sample": {"diameter": 8, "height": 16, "radius": 1, "packing": "fcc", "seed": 1},
    "material": {"kr": 8000, "nu": 0.2, "density": 1},
    "contact": {"friction": 0.6},
    "loading": {"platen_velocity": 0.05, "dt": "auto", "max_strain": 0.2, "slow_factor": 0.25}
  })");
}

namespace {

using nlohmann::json;
using orch::RequestError;

Observation planned(std::string id, TestKind test, Conditions c, Observable observable, Role role) {
  return {std::move(id), test, c, observable, 0.0, 0.0, role};
}

}  // namespace

JobSpec check_twin_template(const json& job_template) {
  if (!job_template.is_object()) throw orch::RequestError("job", "must be a JSON object");
  for (const char* key : {"test", "effects"}) {
    if (job_template.contains(key)) {
      throw orch::RequestError(std::string("job.") + key, "is set by the twin; leave it out");
    }
  }
  // The template's "bond" is optional here: it is the centre of the truth draw, and the design's
  // reference UCS is measured at it (the engine's defaults, 64 and 64, when absent).
  json probe = job_template;
  if (!probe.contains("bond")) {
    const BondSpec defaults;
    probe["bond"] = {{"fr0", defaults.fr0_n}, {"fs0", defaults.fs0_n}};
  }
  JobSpec model;
  try {
    parse_job_template(probe, TestKind::btt);
    model = parse_job_template(probe, TestKind::uct);
  } catch (const SpecError& e) {
    throw orch::under("job", e);
  }
  template_platen_speed(model);
  return model;
}

double round_to_two_digits(double x) {
  if (!(x > 0) || !std::isfinite(x)) return x;
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - 1);
  return std::round(x / unit) * unit;
}

json observation_job(const json& job_template, const Observation& o, double fr0_n, double fs0_n,
                     const json& effects) {
  json job = job_template;
  job["test"] = to_string(o.test);
  const Conditions& c = o.conditions;
  json& sample = job["sample"];
  if (c.diameter_m) sample["diameter"] = *c.diameter_m;
  if (c.height_m) sample["height"] = *c.height_m;
  if (c.thickness_m) sample["thickness"] = *c.thickness_m;
  if (c.loading_rate_m_s) job["loading"]["platen_velocity"] = *c.loading_rate_m_s;
  if (is_triaxial(o.test)) job["loading"]["confining_pressure"] = c.confining_pressure_pa;
  job["bond"] = {{"fr0", fr0_n}, {"fs0", fs0_n}};
  if (!effects.empty()) job["effects"] = effects;
  return to_json(parse_job(job));
}

TwinDesign make_twin_design(const json& job_template, const RunJobs& run) {
  TwinDesign d;
  d.job_template = job_template;
  d.model = check_twin_template(job_template);
  const double D = d.model.sample.diameter_m;
  const double H = d.model.sample.height_m;
  const double t = d.model.sample.btt_thickness();
  const double v = template_platen_speed(d.model);
  const Conditions cylinder{D, H, std::nullopt, 0.0, v};
  const Conditions disc{D, std::nullopt, t, 0.0, v};

  // The reference UCS: the template's UCT at its own (or the engine's default) bond strengths,
  // without any effect, so it is the same for every twin of this template.
  const Observation base =
      planned("uct-peak", TestKind::uct, cylinder, Observable::peak_load, Role::calibration);
  const json result =
      run({observation_job(job_template, base, d.model.bond.fr0_n, d.model.bond.fs0_n, {})}).at(0);
  const json ucs = result.value("strength", json());
  if (!ucs.is_number() || !(ucs.get<double>() > 0)) {
    throw std::runtime_error("the template's base UCT reported no strength: " + result.dump());
  }
  d.base_ucs_pa = ucs.get<double>();
  // Rounded, so that a last-digit difference between engine builds does not change the design.
  d.p_low_pa = round_to_two_digits(kLowConfinement * d.base_ucs_pa);
  d.p_high_pa = round_to_two_digits(kHighConfinement * d.base_ucs_pa);

  Conditions low = cylinder, high = cylinder, squat = cylinder, large_disc = disc, fast = cylinder,
             fast_disc = disc;
  low.confining_pressure_pa = d.p_low_pa;
  high.confining_pressure_pa = d.p_high_pa;
  // H/D = 1: the platens constrain the whole specimen, so an effect on how it fails in shear
  // (compression coupling, rate, the interaction range, heterogeneity) moves its strength apart
  // from the slender UCT's (docs/effects.md, "Signatures"). It replaced a 1.5x cylinder, the
  // dearest run of a model point and the observation that varied most between null twins
  // (docs/diagnosis-measurements.md).
  squat.height_m = D;
  large_disc.diameter_m = 1.5 * D;
  large_disc.thickness_m = 1.5 * t;
  fast.loading_rate_m_s = fast_disc.loading_rate_m_s = kFastSpeedFactor * v;
  using enum Observable;
  using enum Role;
  d.observations = {base,
                    planned("uct-modulus", TestKind::uct, cylinder, youngs_modulus, calibration),
                    planned("btt-peak", TestKind::btt, disc, peak_load, calibration)};
  d.observations.push_back(planned("tri-low", TestKind::triaxial, low, peak_load, calibration));
  // The disc at 4x the speed: the inertial gain of a faster loading (rate) shows on the disc as on
  // the cylinder, and more (docs/effects.md, "Signatures": its rate slope +0.25 against the UCT's
  // +0.14), so a calibration that has it can fix rate's parameter and the fast UCT tests it.
  d.observations.push_back(planned("btt-fast", TestKind::btt, fast_disc, peak_load, calibration));
  d.observations.push_back(planned("tri-high", TestKind::triaxial, high, peak_load, held_out));
  d.observations.push_back(planned("uct-squat", TestKind::uct, squat, peak_load, held_out));
  d.observations.push_back(planned("btt-large", TestKind::btt, large_disc, peak_load, held_out));
  d.observations.push_back(planned("uct-fast", TestKind::uct, fast, peak_load, held_out));
  // The strain at the UCT's peak: read from the base UCT's run (no job of its own), and the
  // observable that packing, rate, compression coupling and interaction range move most once the
  // strengths are re-fitted (docs/effects.md, "Signatures").
  d.observations.push_back(
      planned("uct-peak-strain", TestKind::uct, cylinder, peak_strain, held_out));
  return d;
}

}  // namespace rockcal::diagnosis
