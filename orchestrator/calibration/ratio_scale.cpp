#include "orchestrator/calibration/ratio_scale.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "orchestrator/calibration/algorithms.hpp"
#include "orchestrator/calibration/nlopt_bridge.hpp"
#include "orchestrator/calibration/search_space.hpp"

namespace rockcal::calibration {
namespace {

// The best point on the scale line through an evaluated point (its s fixed), within the bounds.
struct LineOptimum {
  double shift;   // of m = mean log strength
  double misfit;  // predicted misfit there
};

class RatioSearch {
 public:
  RatioSearch(Ledger& ledger, const CalibrationCampaign& campaign, double degree,
              HomogeneityChecks& checks)
      : ledger_(ledger),
        campaign_(campaign),
        box_(log_box(campaign)),
        degree_(degree),
        checks_(checks) {}

  void run() {
    search_ratio();
    scale_steps();
  }

 private:
  LineOptimum line_optimum(const EvaluationRecord& r) const {
    const RatioCoords rc = ratio_coords(r.point);
    const LogErrors e = log_errors(*r.loads, ledger_.targets());
    const Weights w = ledger_.weights();
    const double free_shift = scale_shift(e, w, degree_);
    const double shift = clamp_to(rc.m + free_shift, m_range(box_, rc.s)) - rc.m;
    const double du = e.uct + degree_ * shift;
    const double db = e.btt + degree_ * shift;
    return {shift, w.uct * du * du + w.btt * db * db};
  }

  // The scale for a new s, predicted from the evaluated point nearest in s.
  double predicted_m(double s) const {
    const Range mr = m_range(box_, s);
    const EvaluationRecord* nearest = nullptr;
    for (const EvaluationRecord& r : ledger_.history()) {
      if (!r.loads) continue;
      if (!nearest ||
          std::abs(ratio_coords(r.point).s - s) < std::abs(ratio_coords(nearest->point).s - s)) {
        nearest = &r;
      }
    }
    if (!nearest) return 0.5 * (mr.lo + mr.hi);
    const double m = ratio_coords(nearest->point).m;
    return clamp_to(m + line_optimum(*nearest).shift, mr);
  }

  double ratio_misfit(double s) {
    s = clamp_to(s, s_range(box_));
    const EvaluationRecord r =
        ledger_.evaluate_one(point_from_ratio_coords({s, predicted_m(s)}), "ratio");
    return r.loads ? line_optimum(r).misfit : r.misfit;
  }

  // Where to start on s: interpolated between the evaluated ratios that bracket the target ratio,
  // else at the evaluated s closest to it. Returns {s0, initial step}.
  std::pair<double, double> start() const {
    const Range sr = s_range(box_);
    const double target = std::log(ledger_.targets().uct_n / ledger_.targets().btt_n);
    std::vector<std::pair<double, double>> g;  // (s, ln ratio - ln target ratio)
    for (const EvaluationRecord& r : ledger_.history()) {
      if (r.loads)
        g.push_back({ratio_coords(r.point).s, std::log(r.loads->uct_n / r.loads->btt_n) - target});
    }
    std::sort(g.begin(), g.end());
    const double default_step = 0.1 * (sr.hi - sr.lo);
    if (g.empty()) return {0.5 * (sr.lo + sr.hi), default_step};
    for (std::size_t i = 0; i + 1 < g.size(); ++i) {
      const auto [sa, ga] = g[i];
      const auto [sb, gb] = g[i + 1];
      if (ga * gb <= 0 && sb > sa) {
        const double s0 = ga == gb ? sa : sa - ga * (sb - sa) / (gb - ga);
        return {s0, std::clamp(0.5 * (sb - sa), 1e-3, default_step)};
      }
    }
    auto closest = std::min_element(g.begin(), g.end(), [](const auto& a, const auto& b) {
      return std::abs(a.second) < std::abs(b.second);
    });
    return {closest->first, default_step};
  }

  void search_ratio() {
    const Range sr = s_range(box_);
    auto algorithm = nlopt_algorithm(campaign_.algorithm).value_or(nlopt::LN_BOBYQA);
    // A global method would spend the budget on a line; the 1-D search is always local.
    if (algorithm == nlopt::GN_DIRECT_L || algorithm == nlopt::GN_CRS2_LM)
      algorithm = nlopt::LN_BOBYQA;
    nlopt::opt opt(algorithm, 1);
    opt.set_lower_bounds({sr.lo});
    opt.set_upper_bounds({sr.hi});
    const auto [s0, step] = start();
    std::vector<double> x = {clamp_to(s0, sr)};
    opt.set_initial_step(std::vector<double>{step});
    // Stop once the ratio is within about half the tolerance: the scale step does the rest.
    const Weights w = ledger_.weights();
    const double half_tol = 0.5 * std::log1p(campaign_.tolerance);
    opt.set_stopval(w.uct * w.btt / (w.uct + w.btt) * half_tol * half_tol);
    // F_s0/F_r0 to a quarter of the tolerance; and stop on a plateau (an unreachable ratio makes
    // the misfit flat where a mechanism saturates).
    opt.set_xtol_abs(0.25 * std::log1p(campaign_.tolerance));
    opt.set_ftol_rel(1e-3);
    opt.set_maxeval(10 * campaign_.max_evaluations);  // the ledger's budget ends it first
    minimise(opt, x, [this](const std::vector<double>& s) { return ratio_misfit(s[0]); });
  }

  const EvaluationRecord* best_on_lines() const {
    const EvaluationRecord* best = nullptr;
    double best_misfit = std::numeric_limits<double>::infinity();
    for (const EvaluationRecord& r : ledger_.history()) {
      if (!r.loads) continue;
      const double f = line_optimum(r).misfit;
      if (f < best_misfit) best_misfit = f, best = &r;
    }
    return best;
  }

  // Newton steps on the scale: each uses the newest point's own residual, so an exponent that is
  // only roughly p still converges in two or three steps.
  void scale_steps() {
    const EvaluationRecord* from = best_on_lines();
    if (!from) return;
    EvaluationRecord current = *from;
    for (int step = 0; step < 3; ++step) {
      const LineOptimum opt = line_optimum(current);
      if (std::abs(opt.shift) < 1e-9) return;
      const RatioCoords rc = ratio_coords(current.point);
      const std::size_t before = ledger_.history().size();
      const EvaluationRecord previous = current;
      current = ledger_.evaluate_one(point_from_ratio_coords({rc.s, rc.m + opt.shift}), "scale");
      if (ledger_.history().size() == before || !current.loads) return;
      // A large enough step is a check on one ratio line: did the ratio stay put?
      if (std::abs(opt.shift) >= std::log(kMinCheckScale)) {
        checks_.checks.push_back(
            measure_homogeneity(previous, current, campaign_.homogeneity_tolerance));
        if (!checks_.checks.back().holds) return;
      }
    }
  }

  Ledger& ledger_;
  const CalibrationCampaign& campaign_;
  LogBox box_;
  double degree_;
  HomogeneityChecks& checks_;
};

}  // namespace

void ratio_then_scale(Ledger& ledger, const CalibrationCampaign& campaign, double degree,
                      HomogeneityChecks& checks) {
  RatioSearch(ledger, campaign, degree, checks).run();
}

}  // namespace rockcal::calibration
