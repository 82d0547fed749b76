#include "orchestrator/calibration/stiffness.hpp"

#include <algorithm>
#include <cmath>

#include <nlopt.hpp>

#include "engine/units.hpp"
#include "orchestrator/calibration/nlopt_bridge.hpp"
#include "orchestrator/calibration/sentence.hpp"
#include "orchestrator/ensemble.hpp"

namespace rockcal::calibration {
namespace {

using nlohmann::json;

// The template's stiffness field: "kr" when it states K_r, else "youngs_modulus" (eq. 3's E).
const char* stiffness_field(const json& job_template) {
  const json* m = job_template.contains("material") ? &job_template.at("material") : nullptr;
  return m && m->contains("kr") ? "kr" : "youngs_modulus";
}

// Whether the template bonds beyond touching neighbours (an interaction range above 1).
bool bonds_beyond_touching(const json& job_template) {
  const json::json_pointer factor("/effects/interaction_range/factor");
  return job_template.contains(factor) && job_template.at(factor).is_number() &&
         job_template.at(factor).get<double>() > 1.0;
}

JobSpec spec_at(const CalibrationCampaign& c, const StiffnessSetting& s) {
  json job = c.job_template;
  job.merge_patch(stiffness_patch(c.job_template, s));
  return parse_job_template(job, TestKind::elastic, BondSpec{c.fr0_n.hi, c.fs0_n.hi});
}

double kr_at(const CalibrationCampaign& c, const StiffnessSetting& s) {
  const JobSpec spec = spec_at(c, s);
  return bond_stiffness(spec, spec.sample.radius_m).kr_n_m;
}

class Stage {
 public:
  Stage(const CalibrationCampaign& c, Evaluator& e) : c_(c), evaluator_(e) {}

  // One elastic run at a setting (its packings side by side), recorded.
  const StiffnessRun& run(const StiffnessSetting& s, const std::string& phase) {
    const ProbeRequest probe{{c_.fr0_n.hi, c_.fs0_n.hi},
                             c_.sample_seed,
                             c_.seed_matters ? kStiffnessPackings : 1,
                             TestKind::elastic,
                             stiffness_patch(c_.job_template, s)};
    StiffnessRun r;
    r.phase = phase;
    r.setting = s;
    r.kr_n_m = kr_at(c_, s);
    const std::vector<orch::Ensemble> out = evaluator_.probe_batch({&probe, 1});
    std::vector<double> e, nu;
    for (const orch::Realisation& x :
         out.empty() ? std::vector<orch::Realisation>{} : out[0].realisations) {
      r.job_ids.push_back(x.job_id);
      if (x.youngs_modulus_pa && x.poisson_ratio) {
        e.push_back(*x.youngs_modulus_pa);
        nu.push_back(*x.poisson_ratio);
      } else if (r.error.empty()) {
        r.error = x.error.empty() ? "the elastic test measured no E or nu" : x.error;
      }
    }
    if (out.empty()) r.error = "the evaluator runs no elastic tests";
    const orch::SampleStats es = orch::sample_stats(e), nus = orch::sample_stats(nu);
    r.packings = nus.n;
    r.youngs_modulus_pa = es.mean;
    r.youngs_modulus_sd = es.sd;
    r.poisson_ratio = nus.mean;
    r.poisson_ratio_sd = nus.sd;
    runs_.push_back(r);
    return runs_.back();
  }

  // NLopt over ln(K_s/K_r) for the target nu; returns the run nearest the target. The start is
  // eq. 3's K_s/K_r for the target (exact for the lattice).
  std::optional<StiffnessRun> search_nu(double target, double scale) {
    const double lo = std::log(ks_over_kr(kStiffnessNuHi)),
                 hi = std::log(ks_over_kr(kStiffnessNuLo));
    nlopt::opt opt(nlopt::LN_NELDERMEAD, 1);
    opt.set_lower_bounds(std::vector<double>{lo});
    opt.set_upper_bounds(std::vector<double>{hi});
    opt.set_initial_step(std::vector<double>{0.7});
    opt.set_maxeval(kStiffnessNuRuns);
    opt.set_stopval(
        kStiffnessNuTolerance);  // within the packings' scatter: more runs would chase it
    opt.set_xtol_abs(1e-3);
    const double start = std::clamp(target, kStiffnessNuLo, kStiffnessNuHi);
    std::vector<double> x = {std::clamp(std::log(ks_over_kr(start)), lo, hi)};
    minimise(opt, x, [&](const std::vector<double>& v) {
      const double nu = nu_for_ks_over_kr(std::exp(std::clamp(v[0], lo, hi)));
      const StiffnessRun& r = run({scale, nu}, "nu");
      // A failed run counts as a miss by 1, beyond any nu a packing has.
      return r.poisson_ratio ? std::abs(*r.poisson_ratio - target) : 1.0;
    });
    std::optional<StiffnessRun> best;
    for (const StiffnessRun& r : runs_) {
      if (!r.poisson_ratio) continue;
      if (!best || std::abs(*r.poisson_ratio - target) < std::abs(*best->poisson_ratio - target))
        best = r;
    }
    return best;
  }

  // NLopt over the long bonds' stiffness exponent n at `at`'s K_s/K_r, for nu at the target less
  // half the tolerance: nu rises with n (softer long bonds) while the UCS/BTS ratio the range
  // gives falls, so the search aims at the smallest n that meets the target. Returns the run
  // nearest that aim, if any measured nu.
  std::optional<StiffnessRun> search_exponent(double target, const StiffnessSetting& at) {
    const double aim = target - 0.5 * kStiffnessNuTolerance;
    nlopt::opt opt(nlopt::LN_NELDERMEAD, 1);
    opt.set_lower_bounds(std::vector<double>{0.0});
    opt.set_upper_bounds(std::vector<double>{kLongBondExponentMax});
    opt.set_initial_step(std::vector<double>{2.0});
    opt.set_maxeval(kLongBondRuns);
    opt.set_stopval(0.25 * kStiffnessNuTolerance);
    opt.set_xtol_abs(0.05);
    std::vector<double> x = {2.0};
    std::optional<StiffnessRun> best;
    minimise(opt, x, [&](const std::vector<double>& v) {
      StiffnessSetting s = at;
      s.long_bond_exponent = std::clamp(v[0], 0.0, kLongBondExponentMax);
      const StiffnessRun& r = run(s, "long_bonds");
      if (!r.poisson_ratio) return 1.0;
      if (!best || std::abs(*r.poisson_ratio - aim) < std::abs(*best->poisson_ratio - aim))
        best = r;
      return std::abs(*r.poisson_ratio - aim);
    });
    return best;
  }

  std::vector<StiffnessRun> runs_;

 private:
  const CalibrationCampaign& c_;
  Evaluator& evaluator_;
};

// The confirming run's errors against the targets: E relative, nu absolute; none without both.
std::optional<double> e_error(const StiffnessResult& r) {
  if (!r.target_youngs_modulus_pa || !r.youngs_modulus_pa) return std::nullopt;
  return *r.youngs_modulus_pa / *r.target_youngs_modulus_pa - 1;
}
std::optional<double> nu_error(const StiffnessResult& r) {
  if (!r.target_poisson_ratio || !r.poisson_ratio) return std::nullopt;
  return *r.poisson_ratio - *r.target_poisson_ratio;
}
bool within(const std::optional<double>& error, double tolerance) {
  return error && std::abs(*error) <= tolerance;
}

std::string why(const StiffnessResult& r) {
  std::string out;
  if (r.target_poisson_ratio) {
    if (!r.poisson_ratio) {
      out = "no elastic run measured nu. ";
    } else if (within(nu_error(r), kStiffnessNuTolerance)) {
      out = sentence("nu %.3f meets the target %.3f at K_s/K_r %.3g", *r.poisson_ratio,
                     *r.target_poisson_ratio, r.ks_over_kr);
      if (r.setting.long_bond_exponent > 0 && r.nu_reached_hi)
        out += sentence(
            " with the bonds beyond touching softened by ((R_i + R_j) / L)^%.3g (as "
            "stiff as the touching ones, they left nu at most %.3f)",
            r.setting.long_bond_exponent, *r.nu_reached_hi);
      out += ". ";
    } else {
      out = sentence("nu %.3f misses the target %.3f: over K_s/K_r from %.3g to %.3g",
                     *r.poisson_ratio, *r.target_poisson_ratio, ks_over_kr(kStiffnessNuHi),
                     ks_over_kr(kStiffnessNuLo));
      if (r.nu_reached_lo && r.nu_reached_hi)
        out +=
            sentence(" the runs measured nu from %.3f to %.3f", *r.nu_reached_lo, *r.nu_reached_hi);
      out += ", the packing's reach";
      if (r.setting.long_bond_exponent > 0)
        out += sentence(
            ", and with the bonds beyond touching softened by ((R_i + R_j) / L)^%.3g "
            "nu %.3f",
            r.setting.long_bond_exponent, *r.poisson_ratio);
      out += ". ";
    }
  }
  if (r.target_youngs_modulus_pa) {
    if (!r.youngs_modulus_pa) {
      out += "no elastic run measured E.";
    } else {
      const double err = *e_error(r);
      out += sentence(within(err, kStiffnessETolerance)
                          ? "E %+.1f%% from the target at K_r %.4g (%.4g x the template's)."
                          : "E %+.1f%% from the target at K_r %.4g (%.4g x the template's): "
                            "misses it.",
                      100 * err, r.kr_n_m, r.setting.scale);
    }
  }
  if (r.packings > 1 && r.poisson_ratio_sd)
    out += sentence(" E and nu are means of %.0f packings (nu sd %.3f between them).", r.packings,
                    *r.poisson_ratio_sd);
  return out;
}

json optional_number(const std::optional<double>& v) {
  return v ? json(*v) : json(nullptr);
}

}  // namespace

bool stiffness_met(const StiffnessResult& r) {
  return (!r.target_youngs_modulus_pa || within(e_error(r), kStiffnessETolerance)) &&
         (!r.target_poisson_ratio || within(nu_error(r), kStiffnessNuTolerance));
}

json stiffness_patch(const json& job_template, const StiffnessSetting& setting) {
  const char* field = stiffness_field(job_template);
  const double value = job_template.at("material").at(field).get<double>();
  json patch = {{"material", {{field, value * setting.scale}, {"nu", setting.nu}}}};
  // Stated whenever the template has a range, 0 included: patches merge into the evaluator's
  // template, and an exponent set at one range must not stay on at the next.
  const bool has_range = job_template.contains(json::json_pointer("/effects/interaction_range"));
  if (has_range || setting.long_bond_exponent > 0)
    patch["effects"] = {
        {"interaction_range", {{"stiffness_exponent", setting.long_bond_exponent}}}};
  return patch;
}

std::optional<StiffnessResult> calibrate_stiffness(const CalibrationCampaign& c,
                                                   Evaluator& evaluator) {
  const ElasticTargets& t = c.targets.elastic;
  if (!t.any()) return std::nullopt;
  StiffnessResult r;
  r.target_youngs_modulus_pa = model_youngs_modulus_pa(c.targets);
  r.target_poisson_ratio = t.poisson_ratio;
  const double template_nu =
      parse_job_template(c.job_template, TestKind::elastic, BondSpec{c.fr0_n.hi, c.fs0_n.hi})
          .material.nu;
  Stage stage(c, evaluator);
  // The nu search at the template's scale; its best run is where E is measured.
  std::optional<StiffnessRun> base =
      t.poisson_ratio ? stage.search_nu(*t.poisson_ratio, 1.0)
                      : std::optional<StiffnessRun>(stage.run({1.0, template_nu}, "start"));
  // A nu above what any K_s/K_r gives, with bonds beyond touching: soften those.
  if (t.poisson_ratio && base && base->poisson_ratio &&
      *base->poisson_ratio < *t.poisson_ratio - kStiffnessNuTolerance &&
      bonds_beyond_touching(c.job_template)) {
    const std::optional<StiffnessRun> soft = stage.search_exponent(*t.poisson_ratio, base->setting);
    if (soft && std::abs(*soft->poisson_ratio - *t.poisson_ratio) <
                    std::abs(*base->poisson_ratio - *t.poisson_ratio))
      base = soft;
  }
  r.setting = base && base->poisson_ratio ? base->setting : StiffnessSetting{1.0, template_nu};
  std::optional<StiffnessRun> last = base;
  if (r.target_youngs_modulus_pa && base && base->youngs_modulus_pa) {
    r.setting.scale = base->setting.scale * *r.target_youngs_modulus_pa / *base->youngs_modulus_pa;
    last = stage.run(r.setting, "confirm");
  }
  for (const StiffnessRun& x : stage.runs_) {
    if (x.phase != "nu" || !x.poisson_ratio) continue;
    r.nu_reached_lo = std::min(r.nu_reached_lo.value_or(*x.poisson_ratio), *x.poisson_ratio);
    r.nu_reached_hi = std::max(r.nu_reached_hi.value_or(*x.poisson_ratio), *x.poisson_ratio);
  }
  if (last) {
    r.youngs_modulus_pa = last->youngs_modulus_pa;
    r.poisson_ratio = last->poisson_ratio;
    r.poisson_ratio_sd = last->poisson_ratio_sd;
    r.packings = last->packings;
  }
  r.kr_n_m = kr_at(c, r.setting);
  r.ks_over_kr = ks_over_kr(r.setting.nu);
  r.runs = std::move(stage.runs_);
  r.why = why(r);
  evaluator.patch_template(stiffness_patch(c.job_template, r.setting));
  return r;
}

json to_json(const StiffnessResult& r, const CalibrationCampaign& c) {
  json runs = json::array();
  for (const StiffnessRun& x : r.runs) {
    runs.push_back({{"phase", x.phase},
                    {"kr", x.kr_n_m},
                    {"ks_over_kr", ks_over_kr(x.setting.nu)},
                    {"nu_input", x.setting.nu},
                    {"long_bond_exponent", x.setting.long_bond_exponent},
                    {"youngs_modulus_pa", optional_number(x.youngs_modulus_pa)},
                    {"poisson_ratio", optional_number(x.poisson_ratio)},
                    {"youngs_modulus_sd", optional_number(x.youngs_modulus_sd)},
                    {"poisson_ratio_sd", optional_number(x.poisson_ratio_sd)},
                    {"packings", x.packings},
                    {"job_ids", x.job_ids},
                    {"error", x.error}});
  }
  json e = nullptr, nu = nullptr;
  if (r.target_youngs_modulus_pa) {
    e = {{"target", *r.target_youngs_modulus_pa},
         {"measured", optional_number(r.youngs_modulus_pa)},
         {"relative_error", optional_number(e_error(r))},
         {"met", within(e_error(r), kStiffnessETolerance)}};
  }
  if (r.target_poisson_ratio) {
    nu = {{"target", *r.target_poisson_ratio},
          {"measured", optional_number(r.poisson_ratio)},
          {"error", optional_number(nu_error(r))},
          {"met", within(nu_error(r), kStiffnessNuTolerance)},
          {"reached", {optional_number(r.nu_reached_lo), optional_number(r.nu_reached_hi)}}};
  }
  json j = {{"measure", "elastic"},
            {"template_field", stiffness_field(c.job_template)},
            {"scale", r.setting.scale},
            {"nu_input", r.setting.nu},
            {"kr", r.kr_n_m},
            {"ks_over_kr", r.ks_over_kr},
            {"long_bond_exponent", r.setting.long_bond_exponent},
            {"youngs_modulus_pa", e},
            {"poisson_ratio", nu},
            {"met", stiffness_met(r)},
            {"packings", r.packings},
            {"poisson_ratio_sd", optional_number(r.poisson_ratio_sd)},
            {"runs", runs},
            {"why", r.why}};
  if (c.targets.scaling && c.targets.lab) {
    const Scaling& s = *c.targets.scaling;
    auto lab = [&](const std::optional<double>& v) {
      return v ? json(s.stress_to_lab(*v)) : json(nullptr);
    };
    j["lab"] = {{"youngs_modulus_pa",
                 {{"target", c.targets.elastic.youngs_modulus_pa
                                 ? json(*c.targets.elastic.youngs_modulus_pa)
                                 : json(nullptr)},
                  {"measured", lab(r.youngs_modulus_pa)}}}};
  }
  return j;
}

}  // namespace rockcal::calibration
