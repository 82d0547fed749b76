#include "orchestrator/calibration/bayes/next_test.hpp"

#include <algorithm>
#include <cmath>

#include "orchestrator/calibration/bayes/box.hpp"
#include "orchestrator/calibration/sentence.hpp"
#include "orchestrator/calibration/specimen.hpp"
#include "orchestrator/inference/emulator/runs.hpp"

namespace rockcal::calibration {
namespace {

constexpr double kSquatHeightToDiameter = 1.0;

// The posterior's mean and its covariance's long axis (unit box).
struct Axis {
  Eigen::Vector2d mean, direction;
  double variance = 0.0;
};

Axis long_axis(const inference::PosteriorGrid& g) {
  Axis a;
  a.mean = g.points.transpose() * g.weight;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (int i = 0; i < g.points.rows(); ++i) {
    const Eigen::Vector2d d = g.points.row(i).transpose() - a.mean;
    cov += g.weight(i) * d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  a.direction = eig.eigenvectors().col(1);
  a.variance = eig.eigenvalues()(1);
  return a;
}

struct Measured {
  std::string observable, unit;
  std::vector<ObservableValue> values;  // at the two ends
  double slope = 0.0;                   // d ln value / d (unit length along the axis)
  double shrinkage = 0.0;               // 1 - new axis sd / old
  bool resolved = false;
};

double shrink(double variance, double slope, double sd) {
  return 1.0 - std::sqrt(sd * sd / (variance * slope * slope + sd * sd));
}

}  // namespace

std::optional<Suggestion> next_test(const Emulators& m,
                                    const std::vector<EvaluationRecord>& history,
                                    const CalibrationCampaign& c, Evaluator& evaluator,
                                    int packings) {
  const Axis axis = long_axis(m.grid);
  const double half = 1.645 * std::sqrt(axis.variance);
  Eigen::Vector2d ends[2] = {axis.mean - half * axis.direction, axis.mean + half * axis.direction};
  for (Eigen::Vector2d& e : ends) e = e.cwiseMax(0.0).cwiseMin(1.0);
  const double length = (ends[1] - ends[0]).norm();
  if (!(length > 1e-6)) return std::nullopt;
  const BondPoint at[2] = {from_unit(ends[0], c), from_unit(ends[1], c)};
  // A lab value of any of them is taken as known to the larger of the two targets' uncertainties.
  const double lab_sd = std::max(c.inference.lab_uct, c.inference.lab_btt);
  std::vector<Measured> measured;

  // The UCT's Young's modulus: every run measured it; its emulator gives the change.
  std::vector<inference::PointRuns> moduli;
  for (const EvaluationRecord& r : history) {
    if (!r.uct || !r.uct->modulus.mean || !(*r.uct->modulus.mean > 0)) continue;
    moduli.push_back({to_unit(r.point, c), {std::log(*r.uct->modulus.mean)}});
  }
  if (moduli.size() >= 3) {
    const inference::Gp gp = inference::fit_gp(inference::gp_data(moduli));
    Measured k{"the UCT's Young's modulus", "Pa", {}, 0, 0, false};
    double v[2];
    for (int e = 0; e < 2; ++e) {
      const inference::Prediction p = predict(gp, ends[e]);
      v[e] = p.mean;
      k.values.push_back({at[e], std::exp(p.mean), std::nullopt});
    }
    k.slope = (v[1] - v[0]) / length;
    const double noise = std::sqrt(predict(gp, ends[0]).var + predict(gp, ends[1]).var);
    k.resolved = std::abs(v[1] - v[0]) > 2 * noise;
    measured.push_back(k);
  }

  // Tests run at the two ends, `packings` each.
  const Specimen& sp = c.model_specimen;
  const double confinement =
      kTriaxialConfinement * uct_strength_pa(c.targets.model_loads_n.uct_n, sp);
  struct Probe {
    std::string observable;
    TestKind test;
    nlohmann::json patch;
  };
  const std::vector<Probe> menu = {
      {sentence("a triaxial peak load at a confinement of %.3g Pa (%.3g x the target UCS)",
                confinement, kTriaxialConfinement),
       TestKind::triaxial,
       {{"loading", {{"confining_pressure", confinement}}}}},
      {sentence("the BTT peak load of a disc of %.3g x the diameter (%.4g, model units)",
                kBttSizeFactor, kBttSizeFactor * sp.diameter_m),
       TestKind::btt,
       {{"sample",
         {{"diameter", kBttSizeFactor * sp.diameter_m},
          {"thickness", kBttSizeFactor * sp.thickness_m}}}}},
      {sentence("the peak load of a squat UCT (H/D = %.3g)", kSquatHeightToDiameter),
       TestKind::uct,
       {{"sample", {{"height", kSquatHeightToDiameter * sp.diameter_m}}}}}};
  const int n = c.seed_matters ? std::max(1, packings) : 1;
  std::vector<ProbeRequest> probes;
  for (const Probe& p : menu) {
    for (const BondPoint& b : at) probes.push_back({b, c.sample_seed + 100000, n, p.test, p.patch});
  }
  const std::vector<orch::Ensemble> out = evaluator.probe_batch(probes);
  for (std::size_t k = 0; k < menu.size() && 2 * k + 1 < out.size(); ++k) {
    const orch::SampleStats& a = out[2 * k].peak_load;
    const orch::SampleStats& b = out[2 * k + 1].peak_load;
    if (!a.mean || !b.mean || !(*a.mean > 0) || !(*b.mean > 0)) continue;
    Measured t{menu[k].observable, "N", {}, 0, 0, false};
    t.values = {{at[0], *a.mean, a.se}, {at[1], *b.mean, b.se}};
    const double diff = std::log(*b.mean / *a.mean);
    t.slope = diff / length;
    // Resolved only against the scatter: one packing's sd in ln from the targets' runs when the
    // probes have no standard error.
    const auto scatter = [&](int e) {
      return std::sqrt(inference::run_noise_at(m.uct.hyper, ends[e]) +
                       inference::run_noise_at(m.btt.hyper, ends[e]));
    };
    const double se_a = a.se ? *a.se / *a.mean : scatter(0);
    const double se_b = b.se ? *b.se / *b.mean : scatter(1);
    t.resolved = std::abs(diff) > 2 * std::hypot(se_a, se_b);
    measured.push_back(t);
  }
  if (measured.empty()) return std::nullopt;
  for (Measured& k : measured)
    k.shrinkage = k.resolved ? shrink(axis.variance, k.slope, lab_sd) : 0.0;

  Suggestion s;
  s.expected_shrinkage = true;
  for (const Measured& k : measured) s.candidates.push_back({k.observable, k.shrinkage});
  const Measured& top = *std::max_element(
      measured.begin(), measured.end(),
      [](const Measured& a, const Measured& b) { return a.shrinkage < b.shrinkage; });
  if (!(top.shrinkage > 0)) {
    s.observable = "none of the engine's further tests";
    s.why =
        "none of the UCT's modulus, a triaxial peak, a wider disc or a squat UCT changes "
        "beyond the runs' scatter between the region's two ends";
    return s;
  }
  s.observable = top.observable;
  s.unit = top.unit;
  s.values = top.values;
  s.spread = std::abs(std::log(top.values.back().value / top.values.front().value));
  s.why =
      sentence("it changes by %.3g%% between the two ends of the region's long axis",
               100 * std::expm1(s.spread)) +
      sentence(" (F_r0 %.4g -> %.4g", at[0].fr0_n, at[1].fr0_n) +
      sentence(
          ", F_s0 %.4g -> %.4g); measured to %.3g%%, it would shorten that axis by about %.0f%%",
          at[0].fs0_n, at[1].fs0_n, 100 * lab_sd, 100 * top.shrinkage);
  return s;
}

}  // namespace rockcal::calibration
