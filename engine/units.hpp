// Eq. 3 (bond stiffnesses from E, nu, R) and eq. 4 (dimensional scaling lab <-> model).
// This is the one place where units are converted.
#pragma once

#include <optional>

namespace rockcal {

struct JobSpec;

struct BondStiffness {
  double kr_n_m;     // normal
  double ks_n_m;     // each shear direction
  double kb_nm_rad;  // each bending direction (torque per radian)
  double kt_nm_rad;  // twisting
};

// Eq. 3 ratios applied to a given normal stiffness: K_s, K_b, K_t from K_r, nu and the bond radius
// R.
BondStiffness stiffness_from_kr(double kr_n_m, double nu, double radius_m);
// Eq. 3's K_s / K_r (and K_t / K_b) for a nu, and the nu that gives a ratio.
double ks_over_kr(double nu);
double nu_for_ks_over_kr(double ratio);
// Eq. 3 in full: K_r = sqrt(2) E R / (2 (1 - 2 nu)).
double kr_from_youngs_modulus(double youngs_modulus_pa, double nu, double radius_m);
BondStiffness stiffness_from_youngs_modulus(double youngs_modulus_pa, double nu, double radius_m);
// The job's stiffnesses for a bond of mean radius R (kr given directly, or from E).
BondStiffness bond_stiffness(const JobSpec& spec, double radius_m);

// The same material at a finer resolution: particles `factor` times smaller in the same specimen.
// K_r scales with the radius (eq. 3 at a fixed Young's modulus) and the bond strengths with the
// radius squared (a bond carries the stress on a cross-section of order R^2), so the specimen's
// modulus and stresses are the coarse model's to first order; what changes is the cut.
struct Refinement {
  double factor;  // coarse radius / fine radius, > 0
  double radius(double r_m) const { return r_m / factor; }
  double kr(double kr_n_m) const { return kr_n_m / factor; }
  // Multiplied by 1 / factor^2, as the diagnosis always did: its stored jobs keep their identities.
  double strength(double f_n) const { return f_n * (1.0 / (factor * factor)); }
};

// Mass and moment of inertia of a solid sphere.
double sphere_mass(double density_kg_m3, double radius_m);
double sphere_inertia(double mass_kg, double radius_m);

// Stability limit of a particle with the given summed translational and rotational stiffnesses:
// dt_crit = sqrt(2) * sqrt(min(m / sum_k, I / sum_k_rot)) (mass-spring chain; YADE uses the same
// bound).
double critical_time_step(double mass_kg, double inertia_kg_m2, double sum_k_n_m,
                          double sum_k_rot_nm);
// The same for a particle of the job's FCC packing (12 bonds, plus one platen contact).
double critical_time_step(const JobSpec& spec);

// Eq. 4: a lab system (1) and a model system (2) related by dimensionless groups. Forces scale with
// stiffness x length; time follows from m x / (F t^2) being equal in both systems.
struct LabMaterial {
  double youngs_modulus_pa;
  double nu;
  double density_kg_m3;
  double grain_radius_m;
};

struct ModelChoice {
  double kr_n_m;         // K_r2
  double radius_m;       // R2
  double density_kg_m3;  // rho2
};

struct Scaling {
  double kr_lab_n_m;  // K_r1 of the lab grains by eq. 3
  double length;      // x2 / x1
  double mass;        // m2 / m1
  double force;       // F2 / F1
  double time;        // t2 / t1
  double velocity;    // V2 / V1
  double stress;      // sigma2 / sigma1 = force / length^2

  double force_to_model(double f_lab_n) const { return f_lab_n * force; }
  double force_to_lab(double f_model_n) const { return f_model_n / force; }
  double length_to_model(double x_lab_m) const { return x_lab_m * length; }
  double length_to_lab(double x_model_m) const { return x_model_m / length; }
  double stress_to_model(double s_lab_pa) const { return s_lab_pa * stress; }
  double stress_to_lab(double s_model_pa) const { return s_model_pa / stress; }
  double velocity_to_model(double v_lab_m_s) const { return v_lab_m_s * velocity; }
  double time_to_lab(double t_model_s) const { return t_model_s / time; }
};

// length_ratio defaults to R2 / R1 (grain for grain); the seed paper instead fixed the model height
// (x2/x1 = H2/H1 = 945), so it can be given explicitly.
Scaling make_scaling(const LabMaterial& lab, const ModelChoice& model,
                     std::optional<double> length_ratio = std::nullopt);

}  // namespace rockcal
