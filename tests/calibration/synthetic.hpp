// Synthetic evaluators: closed-form "DEMs" with the properties the driver must cope with, plus
// wrappers that add noise, failures, counting, caching and cancellation.
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "orchestrator/calibration/campaign.hpp"
#include "orchestrator/calibration/evaluator.hpp"

namespace rockcal::calibration::testing {

using Model = std::function<PeakLoads(const BondPoint&)>;

// Homogeneous of degree 1, ratio unbounded: UCT = 2500 fr0^0.3 fs0^0.7, BTT = 420 fr0^0.8 fs0^0.2.
PeakLoads power_law(const BondPoint& p);
// Homogeneous of degree 1 with a bounded ratio (a smooth minimum of a tensile and a shear
// mechanism, like a bond that fails by whichever is weaker): UCT/BTT stays within [6.0, 23.8].
PeakLoads smooth_min(const BondPoint& p);
// Not homogeneous: a friction-like constant in the UCT and degree 1.2 in the BTT.
PeakLoads non_homogeneous(const BondPoint& p);

// A deterministic pseudo-random number in [-1, 1] for a point and a seed (so replays agree).
double hash_unit(const BondPoint& p, std::uint64_t seed, std::uint64_t salt);

// A probe's peak load as a closed form of the point (the suggestion's further tests).
using ProbeModel = std::function<double(const BondPoint&, const ProbeRequest&)>;

// Shear saturates: past F_s0 = 2 F_r0 the shear strength no longer governs either test, so both
// loads depend on F_r0 alone and every F_s0 >= 2 F_r0 gives them (power_law below saturation).
PeakLoads saturating(const BondPoint& p);
// A triaxial peak that keeps feeling F_s0 past that saturation (confinement suppresses the tensile
// mode); a BTT of another size follows power_law like the target's.
double saturating_probe(const BondPoint& p, const ProbeRequest& probe);

// An elastic test's E (Pa) and nu as a closed form of the probe (its patch holds the material)
// and the packing's seed.
struct ElasticConstants {
  double youngs_modulus_pa;
  double poisson_ratio;
};
using ElasticModel = std::function<ElasticConstants(const ProbeRequest&, std::uint64_t seed)>;

// Runs each request's realisations (seeds sample_seed, sample_seed + 1, ...) through the model.
struct ModelEvaluator : Evaluator {
  Model model;
  double noise = 0.0;         // relative amplitude, varies with point and seed
  double failure_rate = 0.0;  // share of points that fail, chosen by hash
  std::string failure_error = "synthetic failure";  // the failed runs' error
  std::atomic<int> requests{0};
  std::vector<EvaluationRequest> log;  // every request, in order

  ProbeModel probe_model;      // unset: probes are not supported (probe_batch returns none)
  int probes = 0;              // probes run
  ElasticModel elastic_model;  // the elastic probes' answer; unset: they measure nothing
  nlohmann::json template_patch = nlohmann::json::object();  // what patch_template merged

  explicit ModelEvaluator(Model m, ProbeModel p = nullptr)
      : model(std::move(m)), probe_model(std::move(p)) {}
  EvaluationOutcome evaluate(const EvaluationRequest& r) const;
  std::vector<EvaluationOutcome> evaluate_batch(
      std::span<const EvaluationRequest> requests) override;
  std::vector<orch::Ensemble> probe_batch(std::span<const ProbeRequest> requests) override;
  void patch_template(const nlohmann::json& patch) override { template_patch.merge_patch(patch); }
};

// A job cache in front of another evaluator: answers known requests without running them, counts
// the fresh ones; optionally cancels once `cancel_after` fresh requests have run.
struct CachingEvaluator : Evaluator {
  Evaluator& inner;
  std::map<std::tuple<double, double, std::uint64_t, int>, EvaluationOutcome> cache;
  std::vector<EvaluationRequest> log;
  int fresh = 0;
  int cancel_after = -1;

  explicit CachingEvaluator(Evaluator& e) : inner(e) {}
  std::vector<EvaluationOutcome> evaluate_batch(
      std::span<const EvaluationRequest> requests) override;
};

// A campaign with model-unit targets `targets`, on a demo sample, with the given overrides merged
// in.
nlohmann::json campaign_json(const PeakLoads& targets, const nlohmann::json& overrides = {});
CalibrationCampaign campaign(const PeakLoads& targets, const nlohmann::json& overrides = {});
// What parsing such a campaign (targets 1000 N and 100 N) refuses: the RequestError's text
// ("field: message"), or "accepted".
std::string refusal(const nlohmann::json& overrides);

}  // namespace rockcal::calibration::testing
