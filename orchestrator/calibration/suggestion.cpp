#include "orchestrator/calibration/suggestion.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "orchestrator/calibration/sentence.hpp"
#include "orchestrator/calibration/specimen.hpp"

namespace rockcal::calibration {
namespace {

struct Candidate {
  std::string observable;
  std::string unit;
  std::vector<ObservableValue> values;
};

std::optional<ObservableValue> value_of(const BondPoint& p, const orch::SampleStats& s) {
  if (!s.mean || !std::isfinite(*s.mean) || !(*s.mean > 0)) return std::nullopt;
  return ObservableValue{p, *s.mean, s.se};
}

double spread(const Candidate& c) {
  return std::abs(std::log(c.values.back().value / c.values.front().value));
}

}  // namespace

std::optional<Suggestion> suggest_observable(const ConsistentSet& set, const CalibrationCampaign& c,
                                             Evaluator& evaluator) {
  if (set.unique || set.points.size() < 2) return std::nullopt;
  auto ratio = [](const EvaluationRecord& r) { return r.point.fs0_n / r.point.fr0_n; };
  const auto [lo, hi] = std::minmax_element(
      set.points.begin(), set.points.end(),
      [&](const EvaluationRecord& a, const EvaluationRecord& b) { return ratio(a) < ratio(b); });
  if (ratio(*hi) <= ratio(*lo)) return std::nullopt;
  const EvaluationRecord* ends[2] = {&*lo, &*hi};

  std::vector<Candidate> candidates;
  {
    Candidate modulus{"the UCT's Young's modulus", "Pa", {}};
    for (const EvaluationRecord* e : ends) {
      if (e->uct) {
        if (auto v = value_of(e->point, e->uct->modulus)) modulus.values.push_back(*v);
      }
    }
    if (modulus.values.size() == 2) candidates.push_back(std::move(modulus));
  }
  const Specimen& sp = c.model_specimen;
  const double confinement =
      kTriaxialConfinement * uct_strength_pa(c.targets.model_loads_n.uct_n, sp);
  const double disc = kBttSizeFactor * sp.diameter_m;
  std::vector<ProbeRequest> probes;
  std::vector<Candidate> probed = {
      {sentence("a triaxial peak load at a confinement of %.3g Pa (%.3g x the target UCS)",
                confinement, kTriaxialConfinement),
       "N",
       {}},
      {sentence("the BTT peak load of a disc of %.3g x the diameter (%.4g, model units)",
                kBttSizeFactor, disc),
       "N",
       {}}};
  for (const EvaluationRecord* e : ends) {
    probes.push_back({e->point,
                      c.sample_seed,
                      c.realisations,
                      TestKind::triaxial,
                      {{"loading", {{"confining_pressure", confinement}}}}});
    probes.push_back(
        {e->point,
         c.sample_seed,
         c.realisations,
         TestKind::btt,
         {{"sample", {{"diameter", disc}, {"thickness", kBttSizeFactor * sp.thickness_m}}}}});
  }
  const std::vector<orch::Ensemble> measured = evaluator.probe_batch(probes);
  for (std::size_t i = 0; i < measured.size() && i < probes.size(); ++i) {
    if (auto v = value_of(probes[i].point, measured[i].peak_load))
      probed[i % 2].values.push_back(*v);
  }
  for (Candidate& p : probed) {
    if (p.values.size() == 2) candidates.push_back(std::move(p));
  }
  if (candidates.empty()) return std::nullopt;

  Suggestion s;
  for (const Candidate& k : candidates) s.candidates.push_back({k.observable, spread(k)});
  const Candidate& top = *std::max_element(
      candidates.begin(), candidates.end(),
      [](const Candidate& a, const Candidate& b) { return spread(a) < spread(b); });
  s.observable = top.observable;
  s.unit = top.unit;
  s.values = top.values;
  s.spread = spread(top);
  s.why = sentence(
      "of the observables measured at the consistent set's two ends (F_s0/F_r0 %.3g and %.3g), it "
      "differs most",
      ratio(*lo), ratio(*hi));
  s.why += sentence(": by %.3g%%; a lab value of it picks the member of the set",
                    100 * std::expm1(s.spread));
  return s;
}

}  // namespace rockcal::calibration
