#include "orchestrator/calibration/rock_properties.hpp"

#include <optional>
#include <vector>

#include "orchestrator/calibration/specimen.hpp"

namespace rockcal::calibration {
namespace {

using nlohmann::json;

// A modulus or ratio: the stiffness stage's elastic test where it ran (the interior's, as a lab's
// gauges measure it), else the mean over the estimate's UCT check runs that have it; the UCT's
// mean (for E its pre-peak slope, platen to platen; for nu its interior gauges') is stated beside
// either way.
json measured(const std::optional<EvaluationRecord>& best, bool modulus, double scale,
              std::optional<double> lab, std::optional<double> elastic, int elastic_runs) {
  std::vector<double> values;
  if (best && best->uct) {
    for (const orch::Realisation& x : best->uct->realisations) {
      const std::optional<double>& v = modulus ? x.youngs_modulus_pa : x.poisson_ratio;
      if (v) values.push_back(*v * scale);
    }
  }
  json uct = nullptr;
  if (!values.empty()) {
    double sum = 0;
    for (double v : values) sum += v;
    uct = sum / double(values.size());
  }
  return {{"value", elastic ? json(*elastic * scale) : uct},
          {"runs", elastic ? std::size_t(elastic_runs) : values.size()},
          {"measure", elastic ? "elastic" : "uct"},
          {"uct", uct},
          {"lab", lab ? json(*lab) : json(nullptr)}};
}

}  // namespace

json rock_properties_json(const CalibrationReport& r, const CalibrationCampaign& c) {
  if (!r.posterior) return nullptr;
  const PosteriorSummary& p = *r.posterior;
  const bool lab = c.targets.scaling && c.targets.lab;
  // Loads to the reported units, then each test's strength on its own specimen.
  auto force = [&](double model_n) {
    return lab ? c.targets.scaling->force_to_lab(model_n) : model_n;
  };
  const Specimen& sp = lab ? c.targets.lab->specimen : c.model_specimen;
  auto strength = [&](const PredictedLoad& l, double (*to_pa)(double, const Specimen&)) {
    return json{{"value", to_pa(force(l.mean_n), sp)},
                {"interval", {to_pa(force(l.lo_n), sp), to_pa(force(l.hi_n), sp)}}};
  };
  // A model stress is the lab's times the stress scale; Poisson's ratio has no unit.
  const double stress = lab ? 1.0 / c.targets.scaling->stress : 1.0;
  // The lab's own E and nu: the targets' where the request gave them, else the lab material's.
  std::optional<double> lab_e = c.targets.elastic.youngs_modulus_pa;
  std::optional<double> lab_nu = c.targets.elastic.poisson_ratio;
  if (lab && !lab_e) lab_e = c.targets.lab->material.youngs_modulus_pa;
  if (lab && !lab_nu) lab_nu = c.targets.lab->material.nu;
  const StiffnessResult st = r.stiffness.value_or(StiffnessResult{});
  return {{"units", lab ? "lab" : "model"},
          {"ucs_pa", strength(p.uct, uct_strength_pa)},
          {"bts_pa", strength(p.btt, btt_strength_pa)},
          {"youngs_modulus_pa",
           measured(r.best, true, stress, lab_e, st.youngs_modulus_pa, st.packings)},
          {"poisson_ratio", measured(r.best, false, 1.0, lab_nu, st.poisson_ratio, st.packings)}};
}

}  // namespace rockcal::calibration
