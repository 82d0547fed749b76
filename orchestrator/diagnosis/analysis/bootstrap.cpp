#include "orchestrator/diagnosis/analysis/bootstrap.hpp"

#include <cmath>
#include <random>

#include "orchestrator/diagnosis/analysis/evidence.hpp"
#include "orchestrator/diagnosis/analysis/gap.hpp"
#include "orchestrator/diagnosis/analysis/verdict.hpp"

namespace rockcal::diagnosis {
namespace {

struct Normal {
  std::mt19937_64 engine;
  double spare = 0.0;
  bool has_spare = false;

  double uniform() { return (double(engine() >> 11) + 0.5) * 0x1.0p-53; }
  double operator()() {
    if (has_spare) {
      has_spare = false;
      return spare;
    }
    const double r = std::sqrt(-2.0 * std::log(uniform()));
    const double a = 2.0 * M_PI * uniform();
    spare = r * std::sin(a);
    has_spare = true;
    return r * std::cos(a);
  }
};

// A candidate's residuals in one replicate: re-fitted on its surfaces, anchored to its real run
// when it has one.
std::vector<double> replicate_residuals(const CandidateResult& c,
                                        const std::vector<Target>& targets,
                                        const std::vector<double>& budget,
                                        const std::vector<double>& lab) {
  // A confirmed candidate re-fits on its surfaces as corrected through its real run, so that
  // without noise the replicate lands where the nominal fit did.
  const SurfaceCalibration fit =
      refit_near(c.surfaces, calibration_objective(targets, budget, c.surfaces, lab),
                 c.calibration.z, c.surface_offset);
  const std::vector<double> moved = predict(c.surfaces, fit.z);
  std::vector<double> sim = c.ln_sim();
  for (std::size_t i = 0; i < sim.size(); ++i) sim[i] += moved[i] - c.predicted[i];
  return residuals(sim, lab);
}

}  // namespace

Objective calibration_objective(const std::vector<Target>& targets,
                                const std::vector<double>& budget, const SurfaceSet& surfaces,
                                std::vector<double> lab) {
  Objective o{std::move(lab), std::vector<double>(targets.size(), 0.0)};
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (targets[i].role != Role::calibration || !surfaces.per_target[i]) continue;
    const double scale = std::max(noise_scale(targets[i], budget[i]), kMinNoiseScale);
    o.weight[i] = 1.0 / (scale * scale);
  }
  return o;
}

BootstrapResult bootstrap_verdicts(const DecisionRule& rule,
                                   const std::vector<CandidateResult>& candidates,
                                   const std::vector<Target>& targets,
                                   const std::vector<double>& budget,
                                   const std::vector<double>& judged, int replicates,
                                   std::uint64_t seed) {
  BootstrapResult out;
  if (!candidates[0].fitted) return out;
  Normal normal{std::mt19937_64(seed)};
  const std::vector<double> nominal = ln_lab(targets);
  const std::vector<double> base_spread = held_out_fit_variance(candidates[0], targets, judged);
  for (int r = 0; r < replicates; ++r) {
    std::vector<double> lab = nominal;
    for (std::size_t i = 0; i < lab.size(); ++i) {
      lab[i] += noise_scale(targets[i], judged[i]) * normal();
    }
    const std::vector<double> base_residuals =
        replicate_residuals(candidates[0], targets, budget, lab);
    const HeldOutDensity base = held_out_density(
        base_residuals, targets, judged, predictive_variance(candidates[0], targets, judged));
    std::vector<Contender> contenders;
    for (int i = 1; i < int(candidates.size()); ++i) {
      const CandidateResult& c = candidates[i];
      if (!c.fitted || !c.identifiability || !c.identifiability->identifiable ||
          !c.fits_calibration || wider_not_closer(c)) {
        continue;
      }
      const HeldOutDensity d =
          held_out_density(replicate_residuals(c, targets, budget, lab), targets, judged,
                           predictive_variance(c, targets, judged));
      if (const auto e = evidence_over(d, base)) contenders.push_back({i, *e});
    }
    const int chosen =
        choose_effect(rule, contenders,
                      rms_in_budgets(base_residuals, targets, judged, Role::held_out, base_spread));
    ++out.winners[chosen < 0 ? "" : candidates[chosen].candidate.effect];
    ++out.replicates;
  }
  return out;
}

}  // namespace rockcal::diagnosis
