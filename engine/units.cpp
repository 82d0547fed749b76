#include "engine/units.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/spec.hpp"

namespace rockcal {

double ks_over_kr(double nu) {
  return (1.0 - 3.0 * nu) / (1.0 + nu);
}

double nu_for_ks_over_kr(double ratio) {
  return (1.0 - ratio) / (3.0 + ratio);
}

BondStiffness stiffness_from_kr(double kr, double nu, double radius) {
  BondStiffness k;
  k.kr_n_m = kr;
  k.ks_n_m = ks_over_kr(nu) * kr;
  k.kb_nm_rad = (1.0 - 2.0 * nu) * radius * radius / (24.0 * (1.0 - nu)) * kr;
  k.kt_nm_rad = ks_over_kr(nu) * k.kb_nm_rad;
  return k;
}

double kr_from_youngs_modulus(double e, double nu, double radius) {
  return std::sqrt(2.0) * e * radius / (2.0 * (1.0 - 2.0 * nu));
}

BondStiffness stiffness_from_youngs_modulus(double e, double nu, double radius) {
  return stiffness_from_kr(kr_from_youngs_modulus(e, nu, radius), nu, radius);
}

BondStiffness bond_stiffness(const JobSpec& spec, double radius) {
  if (spec.material.kr_n_m)
    return stiffness_from_kr(*spec.material.kr_n_m, spec.material.nu, radius);
  return stiffness_from_youngs_modulus(*spec.material.youngs_modulus_pa, spec.material.nu, radius);
}

double sphere_mass(double density, double radius) {
  return density * 4.0 / 3.0 * M_PI * radius * radius * radius;
}

double sphere_inertia(double mass, double radius) {
  return 0.4 * mass * radius * radius;
}

double critical_time_step(double mass, double inertia, double sum_k, double sum_k_rot) {
  double ratio = std::numeric_limits<double>::infinity();
  if (sum_k > 0) ratio = std::min(ratio, mass / sum_k);
  if (sum_k_rot > 0) ratio = std::min(ratio, inertia / sum_k_rot);
  return std::sqrt(2.0) * std::sqrt(ratio);
}

double critical_time_step(const JobSpec& spec) {
  const double r = spec.sample.radius_m;
  const BondStiffness k = bond_stiffness(spec, r);
  const double m = sphere_mass(spec.material.density_kg_m3, r);
  // 12 FCC bonds; a shear spring acts on rotation through the lever R. One platen adds K_r.
  const double sum_k = 12.0 * (k.kr_n_m + k.ks_n_m) + k.kr_n_m;
  const double sum_k_rot = 12.0 * (k.ks_n_m * r * r + k.kb_nm_rad + k.kt_nm_rad);
  return critical_time_step(m, sphere_inertia(m, r), sum_k, sum_k_rot);
}

Scaling make_scaling(const LabMaterial& lab, const ModelChoice& model,
                     std::optional<double> length_ratio) {
  if (!(lab.youngs_modulus_pa > 0 && lab.density_kg_m3 > 0 && lab.grain_radius_m > 0 &&
        model.kr_n_m > 0 && model.radius_m > 0 && model.density_kg_m3 > 0)) {
    throw std::invalid_argument("scaling needs positive lab and model quantities");
  }
  Scaling s;
  s.kr_lab_n_m = kr_from_youngs_modulus(lab.youngs_modulus_pa, lab.nu, lab.grain_radius_m);
  s.length = length_ratio.value_or(model.radius_m / lab.grain_radius_m);
  s.mass = model.density_kg_m3 / lab.density_kg_m3 * std::pow(s.length, 3);
  s.force = model.kr_n_m / s.kr_lab_n_m * s.length;
  // m1 x1 / (F1 t1^2) = m2 x2 / (F2 t2^2)  =>  (t2/t1)^2 = (m2/m1)(x2/x1)/(F2/F1)
  s.time = std::sqrt(s.mass * s.length / s.force);
  s.velocity = s.length / s.time;
  s.stress = s.force / (s.length * s.length);
  return s;
}

}  // namespace rockcal
