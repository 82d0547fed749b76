#include "synthetic.hpp"

#include <bit>
#include <cmath>

namespace rockcal::calibration::testing {

PeakLoads power_law(const BondPoint& p) {
  return {2500.0 * std::pow(p.fr0_n, 0.3) * std::pow(p.fs0_n, 0.7),
          420.0 * std::pow(p.fr0_n, 0.8) * std::pow(p.fs0_n, 0.2)};
}

PeakLoads smooth_min(const BondPoint& p) {
  auto soft_min = [](double a, double b) { return 1.0 / std::sqrt(1.0 / (a * a) + 1.0 / (b * b)); };
  // Tension-limited: UCT 2500 fr0, BTT 420 fr0 (ratio 5.95); shear-limited: UCT 5000 fs0 x 1.0,
  // BTT 210 fs0 (ratio 23.8).
  return {soft_min(2500.0 * p.fr0_n, 5000.0 * p.fs0_n), soft_min(420.0 * p.fr0_n, 210.0 * p.fs0_n)};
}

PeakLoads non_homogeneous(const BondPoint& p) {
  return {1750.0 * std::pow(p.fr0_n, 0.3) * std::pow(p.fs0_n, 0.7) + 15000.0,
          150.0 * std::pow(p.fr0_n, 0.9) * std::pow(p.fs0_n, 0.3)};
}

double hash_unit(const BondPoint& p, std::uint64_t seed, std::uint64_t salt) {
  std::uint64_t x = std::bit_cast<std::uint64_t>(p.fr0_n) * 0x9E3779B97F4A7C15ull ^
                    std::bit_cast<std::uint64_t>(p.fs0_n) ^ (seed << 32) ^ salt;
  // splitmix64 finaliser
  x ^= x >> 30, x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 27, x *= 0x94D049BB133111EBull;
  x ^= x >> 31;
  return double(x >> 11) * 0x1.0p-52 - 1.0;
}

EvaluationOutcome ModelEvaluator::evaluate(const EvaluationRequest& r) const {
  std::vector<orch::Realisation> uct, btt;
  for (std::uint64_t seed : orch::realisation_seeds(r.sample_seed, r.realisations)) {
    if (failure_rate > 0 && 0.5 * (hash_unit(r.point, seed, 7) + 1.0) < failure_rate) {
      uct.push_back({seed, 0, "failed", {}, {}, {}, failure_error});
      btt.push_back(uct.back());
      continue;
    }
    const PeakLoads loads = model(r.point);
    uct.push_back({seed,
                   0,
                   "succeeded",
                   loads.uct_n * (1.0 + noise * hash_unit(r.point, seed, 1)),
                   {},
                   {},
                   ""});
    btt.push_back({seed,
                   0,
                   "succeeded",
                   loads.btt_n * (1.0 + noise * hash_unit(r.point, seed, 2)),
                   {},
                   {},
                   ""});
  }
  return outcome_of(orch::make_ensemble(uct), orch::make_ensemble(btt));
}

std::vector<EvaluationOutcome> ModelEvaluator::evaluate_batch(
    std::span<const EvaluationRequest> batch) {
  std::vector<EvaluationOutcome> out;
  for (const EvaluationRequest& r : batch) {
    ++requests;
    log.push_back(r);
    out.push_back(evaluate(r));
  }
  return out;
}

std::vector<orch::Ensemble> ModelEvaluator::probe_batch(std::span<const ProbeRequest> batch) {
  std::vector<orch::Ensemble> out;
  for (const ProbeRequest& r : batch) {
    // Without a model of a test's probes, the evaluator runs none of the batch.
    if (!(r.test == TestKind::elastic ? bool(elastic_model) : bool(probe_model))) return {};
    ++probes;
    std::vector<orch::Realisation> runs;
    for (std::uint64_t seed : orch::realisation_seeds(r.sample_seed, r.realisations)) {
      if (r.test == TestKind::elastic) {
        const ElasticConstants e = elastic_model(r, seed);
        orch::Realisation x{seed, 0, "succeeded", 0.0, 0.0, e.youngs_modulus_pa, ""};
        x.poisson_ratio = e.poisson_ratio;
        runs.push_back(x);
        continue;
      }
      runs.push_back({seed,
                      0,
                      "succeeded",
                      probe_model(r.point, r) * (1.0 + noise * hash_unit(r.point, seed, 3)),
                      {},
                      {},
                      ""});
    }
    out.push_back(orch::make_ensemble(std::move(runs)));
  }
  return out;
}

PeakLoads saturating(const BondPoint& p) {
  return power_law({p.fr0_n, std::min(p.fs0_n, 2.0 * p.fr0_n)});
}

double saturating_probe(const BondPoint& p, const ProbeRequest& probe) {
  if (probe.test == TestKind::triaxial) return power_law(p).uct_n;
  return saturating(p).btt_n;
}

std::vector<EvaluationOutcome> CachingEvaluator::evaluate_batch(
    std::span<const EvaluationRequest> batch) {
  std::vector<EvaluationOutcome> out;
  for (const EvaluationRequest& r : batch) {
    log.push_back(r);
    const auto key = std::make_tuple(r.point.fr0_n, r.point.fs0_n, r.sample_seed, r.realisations);
    auto it = cache.find(key);
    if (it == cache.end()) {
      if (cancel_after >= 0 && fresh >= cancel_after) throw EvaluationCancelled();
      ++fresh;
      it = cache.emplace(key, inner.evaluate_batch(std::span(&r, 1)).front()).first;
    }
    out.push_back(it->second);
  }
  return out;
}

nlohmann::json campaign_json(const PeakLoads& targets, const nlohmann::json& overrides) {
  nlohmann::json j = {
      {"kind", "calibration"},
      {"name", "synthetic"},
      {"job",
       {{"sample", {{"diameter", 10}, {"height", 28}, {"radius", 1}}},
        {"material", {{"kr", 8000}, {"nu", 0.2}, {"density", 1}}}}},
      {"targets",
       {{"uct", {{"peak_load", targets.uct_n}}}, {"btt", {{"peak_load", targets.btt_n}}}}},
      {"bounds", {{"fr0", {1, 1000}}, {"fs0", {1, 1000}}}},
      {"max_evaluations", 40},
      {"tolerance", 0.02}};
  if (overrides.is_object()) j.merge_patch(overrides);  // a null key in overrides deletes it
  return j;
}

CalibrationCampaign campaign(const PeakLoads& targets, const nlohmann::json& overrides) {
  return parse_calibration_campaign(campaign_json(targets, overrides));
}

std::string refusal(const nlohmann::json& overrides) {
  try {
    campaign({1000, 100}, overrides);
  } catch (const orch::RequestError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace rockcal::calibration::testing
