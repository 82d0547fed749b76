#include "orchestrator/calibration/bayes/verdict.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "orchestrator/calibration/bayes/box.hpp"
#include "orchestrator/calibration/bayes/check.hpp"
#include "orchestrator/calibration/bayes/emulators.hpp"
#include "orchestrator/calibration/run_faults.hpp"
#include "orchestrator/calibration/sentence.hpp"

namespace rockcal::calibration {
namespace {

std::string loads_text(const PosteriorSummary& p, const CalibrationCampaign& c) {
  std::string out =
      sentence("UCT %+.3g%%, BTT %+.3g%%", 100 * p.uct.relative_error, 100 * p.btt.relative_error);
  for (std::size_t k = 0; k < p.further.size() && k < c.further.size(); ++k)
    out += ", " + c.further[k].name + sentence(" %+.3g%%", 100 * p.further[k].relative_error);
  return out;
}

std::string region_text(const PosteriorSummary& p) {
  return sentence("the %.0f%% credible interval of F_r0 is [%.4g, %.4g]", 100 * p.level, p.fr0.lo,
                  p.fr0.hi) +
         sentence(" and of F_s0 [%.4g, %.4g]", p.fs0.lo, p.fs0.hi);
}

// The loads whose check runs fall outside what the prediction allows, as "UCT -20.1% (z -3.1)":
// those whose check mean misses the target beyond its acceptance (`missing` true), which the
// prediction alone cannot call met, or those whose check mean meets it all the same.
std::string disagreeing_checks(const PosteriorSummary& p, const Acceptance& a, bool missing) {
  std::string out;
  for (const auto& [name, load, band] :
       {std::tuple{"UCT", &p.uct, a.uct}, std::tuple{"BTT", &p.btt, a.btt}}) {
    if (!load->check || load->check->agrees) continue;
    if ((std::abs(load->check->relative_to_target) > band) != missing) continue;
    out +=
        (out.empty() ? "" : ", ") + std::string(name) +
        sentence(" %+.3g%% (z %+.2g)", 100 * load->check->relative_to_prediction, load->check->z) +
        (missing
             ? ""
             : sentence(", itself %+.3g%% of the target", 100 * load->check->relative_to_target));
  }
  return out;
}

// How the met targets were met: within the tolerance, or only within the lab's stated
// uncertainty (with the ratio the runs could not reach, when that is why).
std::string met_text(const PosteriorSummary& p, const CalibrationCampaign& c, const Acceptance& a,
                     const std::optional<RatioRange>& ratio) {
  const bool in_tolerance = std::abs(p.uct.relative_error) <= c.tolerance &&
                            std::abs(p.btt.relative_error) <= c.tolerance;
  if (in_tolerance)
    return sentence("the predicted loads at the estimate are within %.3g%% of both targets (",
                    100 * c.tolerance) +
           loads_text(p, c) + ")";
  std::string out =
      "the predicted loads at the estimate lie within the lab's stated uncertainty of both "
      "targets (" +
      loads_text(p, c) + sentence("; accepted: UCT %.3g%%, BTT %.3g%%", 100 * a.uct, 100 * a.btt) +
      sentence("), not within the %.3g%% tolerance of the lab's means", 100 * c.tolerance);
  if (ratio && !ratio->target_inside())
    out += sentence(": the target UCT/BTT load ratio %.4g lies outside ", ratio->target) +
           reach_words(*ratio) +
           ", so the model meets this rock only within the scatter its lab states";
  return out;
}

// How far one specimen's peak load scatters about the predicted means (the emulators' packing
// scatter at the estimate), when that is wider than the tolerance the means meet: the means, not
// a single run, meet the targets. Empty when both scatter less.
std::string scatter_text(const PosteriorSummary& p, double tolerance) {
  if (std::max(p.uct.run_sd, p.btt.run_sd) <= tolerance) return "";
  return sentence(
      "; one specimen's peak load scatters about these means with sd %.2g (UCT) and %.2g (BTT) "
      "in ln between packings: the means meet the targets, a single run only within that scatter",
      p.uct.run_sd, p.btt.run_sd);
}

// When the estimate moved after the check runs: where they ran and that the estimate has no run of
// its own, so its loads rest on the emulators alone. Empty when the check was at the estimate.
std::string moved_text(const PosteriorSummary& p) {
  if (!p.estimate_moved() || !p.check_failed.empty()) return "";
  std::string checks;
  for (const auto& [name, load] : {std::pair{"UCT", &p.uct}, std::pair{"BTT", &p.btt}}) {
    if (load->check)
      checks += (checks.empty() ? "" : ", ") + std::string(name) +
                sentence(" %+.3g%%", 100 * load->check->relative_to_target);
  }
  return sentence("; the check runs were made at (F_r0 %.4g, F_s0 %.4g), the estimate before them",
                  p.checked_at->fr0_n, p.checked_at->fs0_n) +
         (checks.empty() ? "" : " (" + checks + " of the targets)") +
         sentence(
             "; fitted on them too, the posterior moved its estimate to (%.4g, %.4g), where no "
             "run has been made: its predicted loads rest on the emulators alone",
             p.estimate.fr0_n, p.estimate.fs0_n);
}

// When the check runs gave no loads: where they ran and why, which leaves the prediction without
// a run to bear it out. Empty when they gave both loads (or none ran).
std::string failed_check_text(const PosteriorSummary& p) {
  if (p.check_failed.empty() || !p.checked_at) return "";
  return sentence("the check runs at (F_r0 %.4g, F_s0 %.4g) gave no loads (", p.checked_at->fr0_n,
                  p.checked_at->fs0_n) +
         p.check_failed + "): no run bears the prediction out there" +
         (p.estimate_moved() ? sentence("; the estimate then moved to (%.4g, %.4g)",
                                        p.estimate.fr0_n, p.estimate.fs0_n)
                             : "");
}

// The runs inside the credible region (of the posterior's resolution) that ended without a peak,
// when the check at the estimate ended so too: the targets then lie where the model's runs give no
// loads, whatever the budget. The fix follows what ended them: runs stopped at loading.max_strain
// only (a stiff, strong specimen's peak strain beyond it) reach a peak with a larger one; runs
// still loading up past the bond-controlled window have no peak the strengths set there. Empty
// otherwise.
std::string no_peak_zone_text(const PosteriorSummary& p,
                              const std::vector<EvaluationRecord>& history) {
  if (!is_no_peak(p.check_failed)) return "";
  int inside = 0, no_peak = 0, at_strain = 0;
  for (const EvaluationRecord& e : history) {
    const bool fine = e.phase.rfind("fine", 0) == 0;
    if (fine != (p.resolution == "fine") || !in_credible_region(p, e.point)) continue;
    ++inside;
    if (e.loads || !is_no_peak(e.error)) continue;
    ++no_peak;
    at_strain += e.error.find("loading.max_strain") != std::string::npos ? 1 : 0;
  }
  const bool strain_only =
      at_strain == no_peak && p.check_failed.find("loading.max_strain") != std::string::npos;
  return sentence(
             "the strengths that would give the targets lie where the runs end without a peak "
             "(%.0f of the %.0f runs inside the %.0f%% region ended without one)",
             no_peak, inside, 100 * p.level) +
         (strain_only
              ? ": they stopped at loading.max_strain with the load still rising, so these "
                "strengths' peaks lie at larger strains; raise loading.max_strain in the job "
                "template"
              : ": the model reaches the targets' UCT/BTT load ratio there only with a UCT that "
                "keeps loading up, so more runs of this specimen map the zone's edge rather than "
                "move it; another interaction range in \"reach\" changes the ratios the peaks "
                "reach");
}

// The bound the estimate itself lies at (within two cells of a grid of grid_cells over the
// bounds), as bounds_reached words it; empty when the estimate lies inside. A region that reaches a
// bound only because it is wide (its emulators unsure, a few fine runs on it) does not press on it:
// its targets are met or missed inside the box, and widening the bounds would change nothing.
std::string bound_pressed(const PosteriorSummary& p) {
  if (p.grid_cells <= 0) return "";
  const double margin = 2.0 / p.grid_cells;
  const double at[] = {p.estimate.fr0_n, p.estimate.fs0_n};
  for (int k = 0; k < 2; ++k) {
    const Range& r = k == 0 ? p.box_fr0 : p.box_fs0;
    if (!(r.lo > 0 && r.hi > r.lo && at[k] > 0)) continue;
    const double u = std::log(at[k] / r.lo) / std::log(r.hi / r.lo);
    if (u < margin) return bound_text(k, false, r);
    if (u > 1 - margin) return bound_text(k, true, r);
  }
  return "";
}

}  // namespace

Acceptance acceptance(const CalibrationCampaign& c) {
  // Only a value the request states widens: a default stands for no knowledge of the lab.
  const InferenceSettings& s = c.inference;
  Acceptance a{c.tolerance, c.tolerance, false};
  if (s.lab_uct_stated) a.uct = std::max(a.uct, s.lab_uct);
  if (s.lab_btt_stated) a.btt = std::max(a.btt, s.lab_btt);
  a.widened = a.uct > c.tolerance || a.btt > c.tolerance;
  return a;
}

void judge_posterior(CalibrationReport& r, const CalibrationCampaign& c) {
  r.consistent = {};
  if (!r.posterior) {
    r.verdict = r.stop_reason == StopReason::cancelled ? Verdict::incomplete : Verdict::failed;
    r.verdict_reason = r.stop_reason == StopReason::cancelled
                           ? "cancelled before the emulators could be fitted"
                           : "fewer than 3 points gave both peak loads: no posterior";
    return;
  }
  const PosteriorSummary& p = *r.posterior;
  r.consistent.unique = p.unique;
  r.consistent.why = p.why;
  r.consistent.fr0 = p.fr0;
  r.consistent.fs0 = p.fs0;
  const Acceptance accepted = acceptance(c);
  const bool met = std::abs(p.uct.relative_error) <= accepted.uct &&
                   std::abs(p.btt.relative_error) <= accepted.btt;
  std::string runs = sentence(" (%.0f runs at %.0f points)", p.runs, p.points);
  if (p.resolution == "fine") {
    runs = sentence(" (the fine specimen: %.0f fine runs at %.0f points", p.runs, p.points) +
           sentence(" on emulators of %.0f coarse runs)", p.coarse_runs);
  } else if (p.resolution == "coarse") {
    runs += "; the fine runs gave no emulator, so this is the coarse specimen's posterior";
  }
  // Faults of the runs themselves, whatever the verdict: no peak, not quasi-static.
  std::string faults;
  for (const std::string& f :
       {no_peak_text(r.history), not_quasi_static_text(r.history, platen_velocity_of(c))}) {
    if (!f.empty()) faults += "; " + f;
  }
  const std::string disagree = disagreeing_checks(p, accepted, true);
  const std::string differ = disagreeing_checks(p, accepted, false);
  const std::string failed_check = failed_check_text(p);
  if (met && !failed_check.empty()) {
    // The prediction meets the targets where the real specimen gives no result.
    r.verdict = Verdict::compromise;
    r.verdict_reason =
        "the predicted loads at the estimate meet the targets (" + loads_text(p, c) + "), but " +
        failed_check +
        (is_no_peak(p.check_failed) ? ": the estimate lies at the edge of strengths without a peak"
                                    : "") +
        runs + "; " + region_text(p) + faults;
    return;
  }
  if (met && !disagree.empty()) {
    // The prediction meets the targets, the real runs at the estimate do not bear it out.
    r.verdict = Verdict::compromise;
    r.verdict_reason =
        "the predicted loads at the estimate meet the targets (" + loads_text(p, c) +
        "), but the check runs there disagree with the prediction beyond the packings' scatter "
        "and the emulators' variance (" +
        disagree +
        sentence(" from the prediction, outside its %.0f%% interval)", 100 * kCheckLevel) +
        ": the emulators are wrong near the estimate; more runs there (a larger " +
        (p.resolution == "fine" ? "\"fidelity\".\"runs\": fine runs" : "\"max_evaluations\"") +
        ") would correct them" + runs + "; " + region_text(p) + moved_text(p) + faults;
    return;
  }
  if (met) {
    r.verdict = Verdict::feasible;
    r.verdict_reason =
        met_text(p, c, accepted, r.ratio) + runs + "; " + region_text(p) +
        (p.unique ? "; the strengths are unique: " : "; NOT unique: ") + p.why +
        (differ.empty()
             ? ""
             : "; the check runs at the estimate differ from the prediction beyond its " +
                   sentence("%.0f%% interval (", 100 * kCheckLevel) + differ +
                   ") but meet the targets themselves") +
        moved_text(p) + scatter_text(p, c.tolerance) + faults;
    return;
  }
  if (r.stop_reason == StopReason::cancelled) {
    r.verdict = Verdict::incomplete;
    r.verdict_reason =
        "cancelled before the predicted loads met both targets (" + loads_text(p, c) + ")";
    return;
  }
  r.verdict = Verdict::compromise;
  const std::string pressed = bound_pressed(p);
  // A region that reaches a bound it does not press on: said beside the cause.
  const std::string wide = pressed.empty() && !p.bounds_reached.empty()
                               ? " (the region reaches " + p.bounds_reached.front() +
                                     ", though the estimate lies inside)"
                               : "";
  const std::string miss =
      "the predicted loads at the estimate miss the targets (" + loads_text(p, c) + ")";
  if (r.ratio && !r.ratio->target_inside()) {
    // The ratio first: no pair of strengths in the box gives it, so no scale of both can.
    r.verdict_reason =
        miss + sentence(": the target UCT/BTT load ratio %.4g lies outside ", r.ratio->target) +
        reach_words(*r.ratio);
    if (const std::string zone = no_peak_zone_text(p, r.history); !zone.empty())
      r.verdict_reason += "; " + zone;
    if (!pressed.empty())
      r.verdict_reason += "; the posterior presses on " + pressed +
                          ": widen \"bounds\" to see whether the ratio moves toward the target "
                          "beyond it; if it does not, the model cannot reach this ratio";
  } else if (!pressed.empty()) {
    r.verdict_reason = miss + ": the posterior presses on " + pressed +
                       "; the targets need strengths beyond it: widen \"bounds\"";
  } else if (const std::string zone = no_peak_zone_text(p, r.history); !zone.empty()) {
    r.verdict_reason = miss + ": " + zone + wide;
  } else if (r.stop_reason == StopReason::budget_exhausted) {
    const std::string budget =
        p.resolution == "fine"
            ? sentence(" when the budget of %.0f runs and %.0f fine runs ran out",
                       c.max_evaluations, c.fine_runs)
            : sentence(" when the budget of %.0f runs ran out", c.max_evaluations);
    r.verdict_reason =
        miss + budget +
        sentence(
            ", with the emulators holding %.0f%% (UCT) and %.0f%% (BTT) of the posterior's "
            "variance: more runs would narrow it",
            100 * p.uct.emulator_share / (1 + p.uct.emulator_share),
            100 * p.btt.emulator_share / (1 + p.btt.emulator_share)) +
        wide;
  } else {
    r.verdict_reason = miss +
                       ", though the emulators know the region well: the model cannot "
                       "meet both loads within " +
                       (accepted.widened ? "the lab's stated uncertainty" : "the tolerance") +
                       " there" + wide;
  }
  r.verdict_reason +=
      runs + "; " + region_text(p) + (failed_check.empty() ? "" : "; " + failed_check) + faults;
}

}  // namespace rockcal::calibration
