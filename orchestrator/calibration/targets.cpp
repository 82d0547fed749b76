#include "orchestrator/calibration/targets.hpp"

namespace rockcal::calibration {
namespace {

double uct_load(const TargetValue& t, const Specimen& s) {
  return t.quantity == TargetQuantity::peak_load ? t.value : uct_load_n(t.value, s);
}

double btt_load(const TargetValue& t, const Specimen& s) {
  return t.quantity == TargetQuantity::peak_load ? t.value : btt_load_n(t.value, s);
}

}  // namespace

Targets resolve_targets(TargetValue uct, TargetValue btt, const Specimen& model_specimen,
                        std::optional<LabCase> lab) {
  Targets t{uct, btt, lab, std::nullopt, {}, {}};
  if (!lab) {
    t.model_loads_n = {uct_load(uct, model_specimen), btt_load(btt, model_specimen)};
    return t;
  }
  t.scaling = make_scaling(lab->material, lab->model, lab->length_ratio);
  t.model_loads_n = {t.scaling->force_to_model(uct_load(uct, lab->specimen)),
                     t.scaling->force_to_model(btt_load(btt, lab->specimen))};
  return t;
}

std::optional<double> model_youngs_modulus_pa(const Targets& targets) {
  const std::optional<double>& e = targets.elastic.youngs_modulus_pa;
  if (!e || !targets.scaling) return e;
  return targets.scaling->stress_to_model(*e);
}

PeakLoads loads_to_lab(const PeakLoads& model_n, const Scaling& scaling) {
  return {scaling.force_to_lab(model_n.uct_n), scaling.force_to_lab(model_n.btt_n)};
}

// Bond strengths are forces, so they map with the force scale like the loads.
BondPoint bonds_to_lab(const BondPoint& model_n, const Scaling& scaling) {
  return {scaling.force_to_lab(model_n.fr0_n), scaling.force_to_lab(model_n.fs0_n)};
}

}  // namespace rockcal::calibration
