#include "orchestrator/calibration/bayes/emulators.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "orchestrator/calibration/bayes/box.hpp"
#include "orchestrator/calibration/run_faults.hpp"
#include "orchestrator/calibration/sentence.hpp"
#include "orchestrator/inference/design/batch_design.hpp"
#include "orchestrator/inference/emulator/runs.hpp"
#include "orchestrator/inference/emulator/two_level.hpp"
#include "orchestrator/inference/posterior/feasibility.hpp"
#include "orchestrator/inference/posterior/region.hpp"

namespace rockcal::calibration {
namespace {

// The standard normal quantile for a two-sided `level` interval, by bisection on erfc.
double two_sided_z(double level) {
  double lo = 0.0, hi = 10.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::sqrt(2.0)) > 1.0 - level ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

PredictedLoad predicted(const inference::Gp& gp, const Eigen::Vector2d& x, double target_n,
                        double lab_sd, double share, double z) {
  const inference::Prediction p = predict(gp, x);
  const double run_var = inference::run_noise_at(gp.hyper, x);
  PredictedLoad l;
  l.target_n = target_n;
  l.mean_n = std::exp(p.mean);
  l.lo_n = std::exp(p.mean - z * std::sqrt(p.var));
  l.hi_n = std::exp(p.mean + z * std::sqrt(p.var));
  l.run_lo_n = std::exp(p.mean - z * std::sqrt(p.var + run_var));
  l.run_hi_n = std::exp(p.mean + z * std::sqrt(p.var + run_var));
  l.relative_error = l.mean_n / target_n - 1.0;
  l.lab_sd = lab_sd;
  l.emulator_sd = std::sqrt(p.var);
  l.run_sd = std::sqrt(run_var);
  l.emulator_share = share;
  return l;
}

}  // namespace

std::vector<inference::Target> inference_targets(const CalibrationCampaign& c) {
  const PeakLoads& t = c.targets.model_loads_n;
  const InferenceSettings& s = c.inference;
  std::vector<inference::Target> out = {{std::log(t.uct_n), s.lab_uct, s.discrepancy},
                                        {std::log(t.btt_n), s.lab_btt, s.discrepancy}};
  for (const FurtherTarget& f : c.further)
    out.push_back({std::log(f.model_n), f.sd, s.discrepancy});
  return out;
}

namespace {

// Each distinct point's runs of each load that had a peak, in ln, on the campaign's unit box.
struct PointsRuns {
  std::vector<BondPoint> points;               // the distinct points with both loads
  std::vector<inference::PointRuns> uct, btt;  // every point with either load (empty otherwise)
  std::vector<std::vector<inference::PointRuns>> further;  // [target][point]
  int runs = 0;                                            // runs with both loads
  // Every run's point with 1 when it gave both loads, 0 when one of its tests had no peak.
  std::vector<Eigen::Vector2d> outcome_at;
  std::vector<double> outcome;
};

// A test's peak load when it had one: a run whose other test had no peak still measured it.
std::optional<double> peak_of(const std::optional<orch::Ensemble>& e) {
  if (!e || !e->peak_load.mean || !std::isfinite(*e->peak_load.mean) || *e->peak_load.mean <= 0)
    return std::nullopt;
  return *e->peak_load.mean;
}

PointsRuns gather(const std::vector<EvaluationRecord>& history, const CalibrationCampaign& c) {
  PointsRuns g;
  g.further.resize(c.further.size());
  std::map<std::pair<double, double>, int> index;  // a point's row in uct, btt and further
  std::set<std::pair<double, double>> both;        // the points with both loads, in g.points
  for (const EvaluationRecord& r : history) {
    if (r.loads || is_no_peak(r.error)) {
      g.outcome_at.push_back(to_unit(r.point, c));
      g.outcome.push_back(r.loads ? 1.0 : 0.0);
    }
    // Each test's emulator learns from every run of it that had a peak: where the UCT is still
    // loading up past the bonds' window the BTT has one all the same.
    const std::optional<double> uct = r.loads ? r.loads->uct_n : peak_of(r.uct);
    const std::optional<double> btt = r.loads ? r.loads->btt_n : peak_of(r.btt);
    if (!uct && !btt) continue;
    const std::pair<double, double> key{r.point.fr0_n, r.point.fs0_n};
    auto [it, fresh] = index.try_emplace(key, int(g.uct.size()));
    if (fresh) {
      g.uct.push_back({to_unit(r.point, c), {}});
      g.btt.push_back({to_unit(r.point, c), {}});
      for (auto& f : g.further) f.push_back({to_unit(r.point, c), {}});
    }
    if (uct) g.uct[it->second].values.push_back(std::log(*uct));
    if (btt) g.btt[it->second].values.push_back(std::log(*btt));
    if (!r.loads) continue;
    if (both.insert(key).second) g.points.push_back(r.point);
    for (std::size_t k = 0; k < g.further.size() && k < r.further_n.size(); ++k) {
      if (r.further_n[k] && *r.further_n[k] > 0)
        g.further[k][it->second].values.push_back(std::log(*r.further_n[k]));
    }
    ++g.runs;
  }
  return g;
}

// The runs' outcomes as the posterior's feasibility (inference/posterior/feasibility.hpp): where
// runs end without a peak the lab's rock, which had one, is not.
inference::RunResults run_results(const PointsRuns& g) {
  inference::RunResults r;
  r.x.resize(Eigen::Index(g.outcome.size()), 2);
  r.has_value.resize(Eigen::Index(g.outcome.size()));
  for (std::size_t i = 0; i < g.outcome.size(); ++i) {
    r.x.row(Eigen::Index(i)) = g.outcome_at[i].transpose();
    r.has_value(Eigen::Index(i)) = g.outcome[i];
  }
  return r;
}

// Whether a run reaches a peak is decided by the strengths' ratio F_s0/F_r0: the model is
// homogeneous of degree one in them (docs/loading-rate.md), so scaling both scales the run's loads
// and strains and leaves the shape of its curve, and whether it has a peak, as it was. The seed
// rock's UCTs at D/R 20 had none from F_s0/F_r0 about 2.4-3.1 (packings differ) at every scale
// from 20 to 290 N. So the feasibility's kernel has its lengths in ln units of the strengths, not
// of the box: 0.1 in ln(F_s0/F_r0), the width of that fuzzy border (a length of the box, 0.05 of
// ln 1000 on the main job's bounds, spanned a factor 1.6 in the ratio and let the border's
// failures and the runs well inside it blur into one), and ten times that in ln(F_r0 F_s0); not
// infinitely far, as the packing, the time step and the seating load do not scale exactly.
constexpr double kRatioLength = 0.1, kScaleLength = 1.0;
// The odds against the nearest runs' outcome, as a pseudo-run of "feasible": where a UCT has no
// peak no packing has been seen to give one, and a floor of 5% (the inference core's default) let
// the no-peak half of the box, flat in the UCT emulator there (no UCT values), hold the 5% tail of
// F_r0's marginal (the main job's F_r0 interval reached 15.5 against a region ending at 18).
constexpr double kFeasiblePrior = 0.01;

inference::FeasibilitySettings feasibility_settings(const CalibrationCampaign& c) {
  const double w0 = std::log(c.fr0_n.hi / c.fr0_n.lo), w1 = std::log(c.fs0_n.hi / c.fs0_n.lo);
  const Eigen::Vector2d ratio(-w0, w1);  // d ln(F_s0/F_r0) per unit of the box
  const Eigen::Vector2d scale(w0, w1);   // d ln(F_r0 F_s0)
  inference::FeasibilitySettings s;
  s.prior_weight = kFeasiblePrior;
  const double a = s.length / kRatioLength, b = s.length / kScaleLength;
  s.metric = a * a * ratio * ratio.transpose() + b * b * scale * scale.transpose();
  return s;
}

// A fine run's outcome replaces the coarse runs' within this distance (the feasibility's, twice
// its kernel's length: 0.2 in ln(F_s0/F_r0)): the fine UCT can lose its peak where the coarse one
// still has one.
constexpr double kFineOutcomeReach = 0.1;

// Where runs ended without a peak, the grid's posterior weighed by the runs' outcomes.
void weigh_by_outcomes(inference::PosteriorGrid& grid, const Emulators& m,
                       const CalibrationCampaign& c) {
  if ((m.outcomes.has_value.array() < 0.5).any())
    inference::apply_feasibility(grid, m.outcomes, m.targets, feasibility_settings(c));
}

void finish(Emulators& m, inference::RunResults outcomes, const CalibrationCampaign& c) {
  m.targets = inference_targets(c);
  m.grid = inference::posterior_on_grid(m.emulators(), m.targets);
  m.outcomes = std::move(outcomes);
  weigh_by_outcomes(m.grid, m, c);
}

}  // namespace

Emulators fit_emulators(const std::vector<EvaluationRecord>& history,
                        const CalibrationCampaign& c) {
  PointsRuns g = gather(history, c);
  if (g.points.size() < 3) throw std::runtime_error("fewer than 3 points with both loads");
  Emulators m;
  // A packing's scatter depends on which bonds fail first (inference/emulator/gp.hpp).
  inference::GpOptions o;
  o.noise_trend = true;
  m.uct = inference::fit_gp(inference::gp_data(g.uct), o);
  m.btt = inference::fit_gp(inference::gp_data(g.btt), o);
  for (const auto& f : g.further) {
    const inference::GpData d = inference::gp_data(f);
    if (d.x.rows() < 3) throw std::runtime_error("fewer than 3 points with a further test's load");
    m.further.push_back(inference::fit_gp(d, o));
  }
  m.points = g.points;
  m.runs = g.runs;
  finish(m, run_results(g), c);
  return m;
}

Emulators fit_fine_emulators(const std::vector<EvaluationRecord>& fine, const Emulators& coarse,
                             const CalibrationCampaign& fine_c) {
  PointsRuns g = gather(fine, fine_c);
  if (g.points.size() < 2) throw std::runtime_error("fewer than 2 fine points with both loads");
  Emulators m;
  m.uct = inference::fit_two_level(coarse.uct, inference::gp_data(g.uct));
  m.btt = inference::fit_two_level(coarse.btt, inference::gp_data(g.btt));
  m.points = g.points;
  m.runs = g.runs;
  m.coarse_runs = coarse.runs;
  finish(m,
         inference::overlaid(coarse.outcomes, run_results(g), kFineOutcomeReach,
                             feasibility_settings(fine_c)),
         fine_c);
  return m;
}

Emulators with_fine_outcomes(const Emulators& coarse, const std::vector<EvaluationRecord>& fine,
                             const CalibrationCampaign& fine_c) {
  Emulators m = coarse;
  finish(m,
         inference::overlaid(coarse.outcomes, run_results(gather(fine, fine_c)), kFineOutcomeReach,
                             feasibility_settings(fine_c)),
         fine_c);
  return m;
}

CalibrationCampaign fine_campaign(const CalibrationCampaign& c) {
  CalibrationCampaign f = c;
  f.job_template.merge_patch(c.fine_patch);
  const double s = c.fine_strength_scale;
  f.fr0_n = {c.fr0_n.lo * s, c.fr0_n.hi * s};
  f.fs0_n = {c.fs0_n.lo * s, c.fs0_n.hi * s};
  return f;
}

std::vector<double> emulator_shares(const Emulators& m) {
  return inference::emulator_share(m.grid, m.targets);
}

BondPoint posterior_estimate(const Emulators& m, const CalibrationCampaign& c) {
  return from_unit(inference::density_peak(m.grid, m.emulators(), m.targets), c);
}

bool in_credible_region(const PosteriorSummary& s, const BondPoint& p) {
  const int n = s.grid_cells;
  const auto cell = [n](double v, const Range& r) {
    const double f = std::log(v / r.lo) / std::log(r.hi / r.lo);
    return std::isfinite(f) && f >= 0 && f < 1 ? int(std::floor(f * n)) : -1;
  };
  const int i = cell(p.fr0_n, s.grid_fr0), j = cell(p.fs0_n, s.grid_fs0);
  if (i < 0 || j < 0) return false;  // outside the grid, which spans the posterior's mass
  return std::any_of(s.region.begin(), s.region.end(),
                     [&](const RegionSpan& r) { return r.j == j && r.i_lo <= i && i <= r.i_hi; });
}

PosteriorSummary summarise(const Emulators& m, const CalibrationCampaign& c, int rounds) {
  const InferenceSettings& s = c.inference;
  // The answer's grid: as fine as the posterior where its mass is (inference::zoomed_grid).
  inference::PosteriorGrid grid = inference::zoomed_grid(m.grid, m.emulators(), m.targets);
  weigh_by_outcomes(grid, m, c);
  const inference::Region region = inference::credible_region(grid, s.level);
  const Eigen::Vector2d peak = inference::density_peak(grid, m.emulators(), m.targets);
  PosteriorSummary p;
  p.level = s.level;
  p.estimate = from_unit(peak, c);
  p.fr0 = {strength_at(region.marginal_lo(0), 0, c), strength_at(region.marginal_hi(0), 0, c)};
  p.fs0 = {strength_at(region.marginal_lo(1), 1, c), strength_at(region.marginal_hi(1), 1, c)};
  p.fr0_extent = {strength_at(region.lo(0), 0, c), strength_at(region.hi(0), 0, c)};
  p.fs0_extent = {strength_at(region.lo(1), 1, c), strength_at(region.hi(1), 1, c)};
  const inference::Region exact =
      inference::credible_region(inference::with_exact_emulators(grid, m.targets), s.level);
  p.fr0_exact = {strength_at(exact.marginal_lo(0), 0, c), strength_at(exact.marginal_hi(0), 0, c)};
  p.fs0_exact = {strength_at(exact.marginal_lo(1), 1, c), strength_at(exact.marginal_hi(1), 1, c)};
  p.box_fr0 = c.fr0_n;
  p.box_fs0 = c.fs0_n;
  p.grid_cells = grid.per_dim;
  p.grid_fr0 = {strength_at(grid.lo(0), 0, c), strength_at(grid.hi(0), 0, c)};
  p.grid_fs0 = {strength_at(grid.lo(1), 1, c), strength_at(grid.hi(1), 1, c)};
  std::vector<std::vector<int>> rows(grid.per_dim);
  for (int cell : region.cells) {
    const std::vector<int> ij = inference::cell_indices(grid, cell);
    rows[ij[1]].push_back(ij[0]);
  }
  for (int j = 0; j < grid.per_dim; ++j) {
    std::sort(rows[j].begin(), rows[j].end());
    for (std::size_t k = 0; k < rows[j].size(); ++k) {
      if (k == 0 || rows[j][k] != rows[j][k - 1] + 1)
        p.region.push_back({j, rows[j][k], rows[j][k]});
      p.region.back().i_hi = rows[j][k];
    }
  }
  for (int k = 0; k < 2; ++k) {
    const Range& r = k == 0 ? c.fr0_n : c.fs0_n;
    if (region.at_lower[k]) p.bounds_reached.push_back(bound_text(k, false, r));
    if (region.at_upper[k]) p.bounds_reached.push_back(bound_text(k, true, r));
  }
  const double z = two_sided_z(s.level);
  const std::vector<double> share = emulator_shares(m);
  const PeakLoads& t = c.targets.model_loads_n;
  p.uct = predicted(m.uct, peak, t.uct_n, s.lab_uct, share[0], z);
  p.btt = predicted(m.btt, peak, t.btt_n, s.lab_btt, share[1], z);
  for (std::size_t k = 0; k < m.further.size(); ++k) {
    const FurtherTarget& f = c.further[k];
    p.further.push_back(predicted(m.further[k], peak, f.model_n, f.sd, share[2 + k], z));
  }
  p.lab_stated = s.lab_stated();
  p.discrepancy = s.discrepancy;
  p.unique_width = s.unique_width;
  p.runs = m.runs;
  p.coarse_runs = m.coarse_runs;
  if (m.coarse_runs > 0) p.resolution = "fine";
  p.points = int(m.points.size());
  p.rounds = rounds;
  const double wr = p.fr0.hi / p.fr0.lo, ws = p.fs0.hi / p.fs0.lo;
  const int pct = int(std::lround(100 * s.level));
  if (!p.bounds_reached.empty()) {
    p.unique = false;
    p.why = "the " + std::to_string(pct) + "% region reaches " + p.bounds_reached.front() +
            ": the targets do not bound the strengths there";
  } else if (wr > s.unique_width || ws > s.unique_width) {
    p.unique = false;
    const double er = p.fr0_exact.hi / p.fr0_exact.lo, es = p.fs0_exact.hi / p.fs0_exact.lo;
    const bool runs_can = er <= s.unique_width && es <= s.unique_width;
    p.why = sentence("the %.0f%% intervals span a factor %.3g in F_r0 and %.3g in F_s0",
                     100 * s.level, wr, ws) +
            sentence(", wider than the stated %.3g: the targets, known to %.3g%%", s.unique_width,
                     100 * std::max(s.lab_uct, s.lab_btt)) +
            sentence(
                ", allow a range of strengths (the emulators hold %.0f%% and %.0f%% of the "
                "posterior's variance)",
                100 * share[0] / (1 + share[0]), 100 * share[1] / (1 + share[1])) +
            sentence("; with exact emulators the factors would be %.3g and %.3g", er, es) +
            (runs_can ? ": more runs can make the strengths unique"
                      : ": more runs cannot make them unique at this uncertainty, another test "
                        "or better-known targets can");
  } else {
    p.unique = true;
    p.why = sentence(
                "the %.0f%% region lies inside the bounds and its intervals span a factor "
                "%.3g in F_r0 and %.3g in F_s0",
                100 * s.level, wr, ws) +
            sentence(", within the stated %.3g", s.unique_width);
  }
  return p;
}

void set_emulated_reach(const Emulators& m, orch::RatioRange& range) {
  // At the points whose UCT peaked (the BTT emulator is defined everywhere): a mean away from the
  // runs is the trend's extrapolation, which on a saturating model ran to twice the runs' ratios.
  const Eigen::MatrixXd& at = m.uct.data.x;
  if (at.rows() == 0) return;
  Eigen::VectorXd mu_u, var_u, mu_b, var_b;
  inference::predict_many(m.uct, at, mu_u, var_u);
  inference::predict_many(m.btt, at, mu_b, var_b);
  const Eigen::ArrayXd d = (mu_u - mu_b).array();
  range.emulated = true;
  range.emulated_lo = std::exp(d.minCoeff());
  range.emulated_hi = std::exp(d.maxCoeff());
}

}  // namespace rockcal::calibration
