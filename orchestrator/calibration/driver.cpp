#include "orchestrator/calibration/driver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include <nlopt.hpp>

#include "orchestrator/calibration/bayes/search.hpp"
#include "orchestrator/calibration/ensemble_size.hpp"
#include "orchestrator/calibration/homogeneity.hpp"
#include "orchestrator/calibration/local_search.hpp"
#include "orchestrator/calibration/ratio_scale.hpp"
#include "orchestrator/calibration/reach.hpp"
#include "orchestrator/calibration/run_faults.hpp"
#include "orchestrator/calibration/sentence.hpp"
#include "orchestrator/calibration/start_design.hpp"
#include "orchestrator/calibration/stiffness.hpp"
#include "orchestrator/calibration/suggestion.hpp"

namespace rockcal::calibration {
namespace {

bool ratio_out_of_reach(const Ledger& ledger) {
  const auto range = ratio_range(ledger.history(), ledger.targets());
  return range && !range->target_inside();
}

// A second check where the answer probably lies: the best start point and its copy scaled toward
// the targets (also when the centre check failed to run).
void probe_near_best(Ledger& ledger, const CalibrationCampaign& c, HomogeneityChecks& h) {
  const EvaluationRecord* best = ledger.best();
  if (!best || (best->index <= 1 && h.checks.front().measured)) return;
  const EvaluationRecord base = *best;
  const double factor = probe_toward_targets(base, c);
  if (factor == 1.0) return;
  const BondPoint partner{base.point.fr0_n * factor, base.point.fs0_n * factor};
  h.checks.push_back(
      measure_homogeneity(base, ledger.evaluate_one(partner, "start"), c.homogeneity_tolerance));
}

void search(Ledger& ledger, const CalibrationCampaign& c, CalibrationReport& report) {
  report.strategy_used = "none";
  const std::vector<EvaluationRecord> start = ledger.evaluate(start_design(c), "start");
  HomogeneityChecks& h = report.homogeneity;
  h.checks.push_back(measure_homogeneity(start[0], start[1], c.homogeneity_tolerance));
  if (c.strategy != Strategy::direct_2d) probe_near_best(ledger, c, h);
  const bool ratio_first =
      c.strategy == Strategy::ratio_scale || (c.strategy == Strategy::automatic && h.holds());
  if (ratio_first) {
    report.strategy_used = "ratio_scale";
    ratio_then_scale(ledger, c, std::clamp(h.degree(), 0.5, 2.0), h);
    // The ratio search has mapped the reachable ratios; a 2-D search cannot leave them either.
    if (ratio_out_of_reach(ledger) && h.holds()) return;
    report.strategy_used = "ratio_scale+direct_2d";
  } else {
    report.strategy_used = "direct_2d";
  }
  const EvaluationRecord* best = ledger.best();
  local_search_with_restarts(ledger, c, best ? best->point : start[0].point);
}

// A further sentence of the verdict's reason, after what it says already.
void append_reason(CalibrationReport& r, const char* label, const std::string& text) {
  if (!r.verdict_reason.empty()) r.verdict_reason += r.verdict_reason.back() == '.' ? " " : ". ";
  r.verdict_reason.append(label).append(": ").append(text);
}

// E and nu are targets too: the reason says how they came out, and a feasible strength answer
// whose stiffness misses is a compromise.
void judge_stiffness(CalibrationReport& r) {
  if (!r.stiffness) return;
  append_reason(r, "Stiffness", r.stiffness->why);
  if (r.verdict == Verdict::feasible && !stiffness_met(*r.stiffness))
    r.verdict = Verdict::compromise;
}

SeedScatter scatter_best(const CalibrationCampaign& c, Evaluator& evaluator,
                         const EvaluationRecord& best) {
  std::vector<ScatterRun> runs = {{best.sample_seed, best.loads, best.error}};
  std::vector<EvaluationRequest> requests;
  for (std::uint64_t seed : c.scatter_seeds) {
    if (seed != best.sample_seed) requests.push_back({best.point, seed});
  }
  const std::vector<EvaluationOutcome> outcomes = evaluator.evaluate_batch(requests);
  for (std::size_t i = 0; i < requests.size() && i < outcomes.size(); ++i) {
    runs.push_back({requests[i].sample_seed, outcomes[i].loads, outcomes[i].error});
  }
  return seed_scatter(std::move(runs));
}

// The best point's re-runs on other packings, as the scatter an ensemble would have to average.
std::optional<ScatterEstimate> scatter_as_estimate(const SeedScatter& s, double tolerance) {
  if (!s.uct || !s.btt || s.uct->runs < 2 || s.btt->runs < 2) return std::nullopt;
  return scatter_estimate(s.uct->stddev_n / s.uct->mean_n, s.btt->stddev_n / s.btt->mean_n,
                          std::min(s.uct->runs, s.btt->runs), tolerance);
}

// One packing's loads pin nothing finer than the packings' spread: when the best point's seed
// scatter is wider than the tolerance, the set found on one packing is not the material's.
void blur_by_scatter(CalibrationReport& r, const CalibrationCampaign& c) {
  const std::optional<ScatterEstimate> s = scatter_as_estimate(r.scatter, c.tolerance);
  if (!r.consistent.unique || !s) return;
  const double cv_uct = *s->cv_uct, cv_btt = *s->cv_btt;
  if (std::max(cv_uct, cv_btt) <= c.tolerance) return;
  r.consistent.unique = false;
  r.consistent.why = sentence(
      "the best point's packing-seed scatter (UCT cv %.3g%%, BTT cv %.3g%%) is wider than the "
      "tolerance: the loads of one packing do not pin the strengths; run every evaluation as an "
      "ensemble (\"realisations\") so that the tolerance counts its standard error",
      100 * cv_uct, 100 * cv_btt);
}

// "Within tolerance" counts each mean's standard error: say so when the loads need it.
std::string within_text(const EvaluationRecord& best, const CalibrationCampaign& c) {
  const PeakLoads& l = *best.loads;
  const PeakLoads& t = c.targets.model_loads_n;
  const double e_uct = relative_error(l.uct_n, t.uct_n), e_btt = relative_error(l.btt_n, t.btt_n);
  if (std::max(std::abs(e_uct), std::abs(e_btt)) <= c.tolerance) {
    return sentence("both peak loads within %.3g%% of their targets", 100 * c.tolerance);
  }
  return sentence(
             "both peak loads within %.3g%% of their targets plus each ensemble mean's "
             "standard error (UCT %+.3g%% +- %.3g%%",
             100 * c.tolerance, 100 * e_uct, 100 * best.rel_se.uct_n) +
         sentence(
             ", BTT %+.3g%% +- %.3g%%): within the packings' scatter, not within the "
             "tolerance",
             100 * e_btt, 100 * best.rel_se.btt_n);
}

// With a fine specimen the answer is the fine one: the coarse search only led there.
bool judge_fine(CalibrationReport& r, const CalibrationCampaign& c) {
  if (c.fine_patch.is_null() || !r.best || !r.best->within_tolerance) return false;
  const FidelityResult* f = r.fidelity ? &*r.fidelity : nullptr;
  if (f && f->met) {
    r.verdict = Verdict::feasible;
    r.verdict_reason = sentence(
        "both peak loads within %.3g%% of their targets on the fine specimen after %.0f fine "
        "evaluations (the consistent set and its uniqueness are the coarse search's)",
        100 * c.tolerance, double(f->steps.size()));
    return true;
  }
  r.verdict = r.stop_reason == StopReason::cancelled ? Verdict::incomplete : Verdict::compromise;
  if (!f || f->steps.empty()) {
    r.verdict_reason = "the coarse search met the targets but the fine specimen was not run";
  } else if (!f->steps.back().fine) {
    r.verdict_reason =
        "the coarse search met the targets; a fine run failed: " + f->steps.back().error;
  } else {
    const PeakLoads& l = *f->steps.back().fine;
    const PeakLoads& t = c.targets.model_loads_n;
    r.verdict_reason = sentence(
        "the coarse search met the targets; after %.0f fine corrections the fine specimen's loads "
        "miss them by UCT %+.3g%%",
        double(f->steps.size()), 100 * relative_error(l.uct_n, t.uct_n));
    r.verdict_reason += sentence(", BTT %+.3g%%", 100 * relative_error(l.btt_n, t.btt_n));
  }
  return true;
}

// The bounds the best point sits on (within 1% of the search's log range), each with its fix: the
// targets want strengths beyond it. Empty when it is inside.
std::string bounds_hit_text(const BondPoint& p, const CalibrationCampaign& c) {
  std::string out;
  auto check = [&out](const char* name, const char* field, double x, const Range& range) {
    const double slack = 0.01 * std::log(range.hi / range.lo);
    const bool lower = std::log(x / range.lo) <= slack;
    if (!lower && std::log(range.hi / x) > slack) return;
    out += (out.empty() ? "" : "; ") + std::string(name) + sentence(" = %.4g N lies on its ", x) +
           (lower ? "lower" : "upper") +
           sentence(" bound %.4g (widen ", lower ? range.lo : range.hi) + field +
           (lower ? sentence(" below %.4g)", range.lo) : sentence(" above %.4g)", range.hi));
  };
  check("F_r0", "\"bounds.fr0\"", p.fr0_n, c.fr0_n);
  check("F_s0", "\"bounds.fs0\"", p.fs0_n, c.fs0_n);
  return out;
}

void judge(CalibrationReport& r, const CalibrationCampaign& c) {
  blur_by_scatter(r, c);
  if (!r.best) {
    r.verdict = Verdict::failed;
    r.verdict_reason = "no evaluation succeeded";
    return;
  }
  if (judge_fine(r, c)) return;
  if (r.best->within_tolerance) {
    r.verdict = Verdict::feasible;
    r.verdict_reason = within_text(*r.best, c);
    // The reason for uniqueness is in the consistent set; a non-unique answer says why here too.
    r.verdict_reason +=
        r.consistent.unique ? "; the strengths are unique" : "; NOT unique: " + r.consistent.why;
    return;
  }
  if (r.stop_reason == StopReason::cancelled) {
    r.verdict = Verdict::incomplete;
    r.verdict_reason = "cancelled before both peak loads were within tolerance";
    return;
  }
  r.verdict = Verdict::compromise;
  const std::string bounds = bounds_hit_text(r.best->point, c);
  const std::string no_peak = no_peak_text(r.history);
  if (r.ratio && !r.ratio->target_inside()) {
    r.verdict_reason = sentence(
        "the target UCT/BTT load ratio %.4g lies outside the range [%.4g, %.4g] the model reached: "
        "both loads cannot be met; best is the weighted log-misfit compromise",
        r.ratio->target, r.ratio->min, r.ratio->max);
    if (!bounds.empty())
      r.verdict_reason += "; the best point lies on the search's bounds: " + bounds;
  } else if (!bounds.empty()) {
    // Not the budget: the search went as far as the bounds let it.
    r.verdict_reason = sentence(
                           "the loads are not both within %.3g%%: the best point lies on the "
                           "search's bounds: ",
                           100 * c.tolerance) +
                       bounds;
  } else if (r.stop_reason == StopReason::budget_exhausted) {
    r.verdict_reason =
        sentence("the budget of %.0f evaluations ran out before both loads were within %.3g%%",
                 c.max_evaluations, 100 * c.tolerance);
  } else {
    r.verdict_reason = sentence(
        "the optimiser converged without both loads within %.3g%% (noise, or "
        "the targets are barely reachable)",
        100 * c.tolerance);
  }
  if (!no_peak.empty()) r.verdict_reason += "; " + no_peak;
  const std::string fast = not_quasi_static_text(r.history, platen_velocity_of(c));
  if (!fast.empty()) r.verdict_reason += "; " + fast;
}

// One calibration at the evaluator's template as it stands: the stiffness stage, the strategy's
// search and what follows it. Returns true, with report.history and report.ratio filled, when
// `leave` says the search's runs send the calibration on to another range: before the steps after
// the search, which would spend runs on an answer this range cannot give.
bool calibrate_at(const CalibrationCampaign& campaign, Evaluator& evaluator,
                  const RunOptions& options, CalibrationReport& report, const LeaveRange& leave) {
  nlopt::srand(campaign.random_seed);  // per thread: seed it in the optimising one
  // The stiffnesses first: the strengths are searched at them.
  try {
    report.stiffness = calibrate_stiffness(campaign, evaluator);
    if (report.stiffness && options.on_stiffness) options.on_stiffness(*report.stiffness);
  } catch (const EvaluationCancelled&) {
    report.stop_reason = StopReason::cancelled;
    report.verdict = Verdict::incomplete;
    return false;
  }
  if (campaign.strategy == Strategy::bayes) {
    if (bayes_calibration(campaign, evaluator, options, report, leave)) return true;
    judge_stiffness(report);
    return false;
  }
  bool cancelled = false;
  try {
    report.ensemble = choose_ensemble_size(campaign, evaluator);
  } catch (const EvaluationCancelled&) {
    cancelled = true;
  }
  CalibrationCampaign c = campaign;  // as run: with the ensemble size chosen
  c.realisations = report.ensemble.realisations;
  Ledger ledger(c, evaluator, options.stop, options.on_evaluation);
  try {
    if (!cancelled) search(ledger, c, report);
  } catch (const SearchDone&) {
  } catch (const EvaluationCancelled&) {
    cancelled = true;
  }
  if (!cancelled && !options.stop.stop_requested()) {
    const std::optional<RatioRange> ratio = ratio_range(ledger.history(), ledger.targets());
    if (leave(ratio, int(ledger.history().size()))) {
      report.history = ledger.history();
      report.ratio = ratio;
      return true;
    }
  }
  // The start batch may already meet the targets (SearchDone before the check): measure anyway.
  if (report.homogeneity.checks.empty() && ledger.history().size() >= 2) {
    report.homogeneity.checks.push_back(
        measure_homogeneity(ledger.history()[0], ledger.history()[1], c.homogeneity_tolerance));
  }
  if (cancelled)
    report.stop_reason = StopReason::cancelled;
  else if (ledger.target_met())
    report.stop_reason = StopReason::tolerance_met;
  else if (ledger.remaining() <= 0)
    report.stop_reason = StopReason::budget_exhausted;
  else
    report.stop_reason = StopReason::converged;

  // After the search: the whole set that meets the targets, the observable that would pin it,
  // and the best point on other packings.
  auto after_search = [&](auto step) {
    if (cancelled || options.stop.stop_requested()) return;
    try {
      step();
    } catch (const SearchDone&) {
    } catch (const EvaluationCancelled&) {
      cancelled = true;
      report.stop_reason = StopReason::cancelled;
    }
  };
  after_search([&] {
    report.trace = trace_valley(ledger, c, report.homogeneity.degree(), c.consistency_evaluations);
  });
  report.history = ledger.history();
  if (const EvaluationRecord* best = ledger.best()) report.best = *best;
  report.ratio = ratio_range(report.history, ledger.targets());
  report.consistent = consistent_set(report.history, report.trace);
  if (report.best && report.best->within_tolerance)
    after_search([&] {
      report.fidelity =
          correct_on_fine(report.history, *report.best, c, report.homogeneity.degree(), evaluator);
    });
  if (c.suggest)
    after_search([&] { report.suggestion = suggest_observable(report.consistent, c, evaluator); });
  if (report.best) after_search([&] { report.scatter = scatter_best(c, evaluator, *report.best); });
  review_ensemble_size(report.ensemble, report.best ? &*report.best : nullptr,
                       scatter_as_estimate(report.scatter, c.tolerance), c.tolerance);
  judge(report, c);
  judge_stiffness(report);
  return false;
}

}  // namespace

CalibrationReport run_calibration(const CalibrationCampaign& campaign, Evaluator& evaluator,
                                  const RunOptions& options) {
  CalibrationReport report;
  const std::vector<double>& ranges = campaign.interaction_ranges;
  if (ranges.empty()) {
    calibrate_at(campaign, evaluator, options, report,
                 [](const std::optional<RatioRange>&, int) { return false; });
    return report;
  }
  // The ranges in order, each with the budget the ranges before it left.
  ReachResult reach;
  reach.listed = ranges;
  int left = campaign.max_evaluations;
  for (std::size_t i = 0;; ++i) {
    evaluator.patch_template(interaction_range_patch(ranges[i]));
    CalibrationCampaign c = campaign;
    c.job_template.merge_patch(interaction_range_patch(ranges[i]));  // what the evaluator runs
    c.max_evaluations = left;
    report = {};
    const bool another = i + 1 < ranges.size();
    bool moved = calibrate_at(c, evaluator, options, report,
                              [&](const std::optional<RatioRange>& ratio, int runs) {
                                return leave_range(ratio, another, left - runs);
                              });
    left -= int(report.history.size());
    reach.tried.push_back({ranges[i], report.history, report.ratio});
    // A search can end before its probe's runs (a bayes search whose emulators soon hold little
    // variance converges and checks): its ratios then decide as the probe's would have.
    moved = moved || (report.stop_reason != StopReason::cancelled &&
                      leave_range(report.ratio, another, left));
    if (moved) continue;
    reach.evaluations_left = left;
    reach.cancelled = report.stop_reason == StopReason::cancelled;
    const PeakLoads& t = campaign.targets.model_loads_n;
    reach.why = reach_why(reach, t.uct_n / t.btt_n);
    // The verdict so far is the last range's: say so when it was not the only one.
    if (reach.tried.size() > 1)
      report.verdict_reason = sentence("at interaction range %.3g, the last tried: ", ranges[i]) +
                              report.verdict_reason;
    append_reason(report, "Reach", reach.why);
    report.reach = std::move(reach);
    return report;
  }
}

CalibrationThread::CalibrationThread(CalibrationCampaign campaign, Evaluator& evaluator,
                                     RecordCallback on_evaluation, int workers)
    : campaign_(std::move(campaign)), result_(promise_.get_future()) {
  thread_ = std::jthread([this, &evaluator, on_evaluation, workers](std::stop_token stop) {
    try {
      promise_.set_value(run_calibration(campaign_, evaluator, {stop, on_evaluation, workers}));
    } catch (...) {
      promise_.set_exception(std::current_exception());
    }
  });
}

CalibrationThread::~CalibrationThread() {
  thread_.request_stop();
  if (thread_.joinable()) thread_.join();
}

CalibrationReport CalibrationThread::wait() {
  return result_.get();
}

}  // namespace rockcal::calibration
