#include "orchestrator/calibration/bayes/search.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <future>
#include <map>

#include "orchestrator/calibration/bayes/box.hpp"
#include "orchestrator/calibration/bayes/check.hpp"
#include "orchestrator/calibration/bayes/emulators.hpp"
#include "orchestrator/calibration/bayes/next_test.hpp"
#include "orchestrator/calibration/bayes/verdict.hpp"
#include "orchestrator/calibration/latin_hypercube.hpp"
#include "orchestrator/inference/design/batch_design.hpp"
#include "orchestrator/inference/posterior/region.hpp"

namespace rockcal::calibration {
namespace {

// Below this share of the posterior's variance in the emulators, more runs narrow the region by
// less than a tenth (sqrt(1.25) = 1.12).
constexpr double kShareStop = 0.25;
// The question answered: the posterior has been unique (narrower than the stated width, inside the
// bounds) with its predicted loads within the tolerance at every refit over at least this many
// runs. More runs would only narrow a region already narrow enough; the budget left is saved.
constexpr int kAnsweredRuns = 10;

// The emulators' share of the posterior's variance under `limit` for every target.
bool shares_below(const Emulators& m, double limit) {
  const std::vector<double> share = emulator_shares(m);
  return std::all_of(share.begin(), share.end(), [&](double s) { return s < limit; });
}
// An answer counts while the emulators hold at most half of the posterior's variance (a share of
// 1: their variance no larger than the targets'): a region made mostly of the emulators' variance
// rests on their plug-in hyperparameters. On the formula twins, stopping on an answer alone left
// the truth outside the region of a twin whose lab draw lay well inside (chi^2 0.74 on 2 degrees
// of freedom): 19 of 24 held it.
constexpr double kAnswerShare = 1.0;
constexpr int kSpaceFilling = 256;  // candidates spread over the box, besides the posterior's own
constexpr int kDensest = 64;        // candidates at the posterior's densest cells
// A fine run is dear and teaches the two-level emulator its discrepancy only near where it runs:
// the fine runs go within this distance (of the unit box) of the current estimate, where the
// answer and its check are, not along a valley of the posterior.
constexpr double kFineReach = 0.05;

struct Run {
  BondPoint point;  // the strengths run: the fine specimen's for a fine run
  std::uint64_t seed;
  std::string phase;
  bool fine = false;
};

// What a batch of runs gave: each run's UCT and BTT, and its further tests' peak loads.
struct Batch {
  std::vector<EvaluationOutcome> outcomes;
  std::vector<std::vector<std::optional<double>>> further;  // [run][further target]
};

struct Flight {
  std::vector<Run> runs;
  std::future<Batch> outcomes;
};

class Search {
 public:
  Search(const CalibrationCampaign& c, Evaluator& e, const RunOptions& o, const LeaveRange& leave)
      : c_(c), evaluator_(e), options_(o), leave_(leave), has_fine_(!c.fine_patch.is_null()) {
    batch_ = c.inference.batch > 0 ? c.inference.batch : std::max(2, o.workers);
    if (has_fine_) fine_c_ = fine_campaign(c);
  }

  bool left() const { return leaving_ && !cancelled_; }
  // The UCT/BTT ratios of the runs, with the reach the coarse emulators put on them.
  std::optional<RatioRange> ratio() const {
    std::optional<RatioRange> r = ratio_range(history_, c_.targets.model_loads_n);
    if (r && model_) set_emulated_reach(*model_, *r);
    return r;
  }

  void run(CalibrationReport& report) {
    launch(start());
    while (!flights_.empty()) {
      Flight f = std::move(flights_.front());
      flights_.pop_front();
      Batch outcomes;
      try {
        outcomes = f.outcomes.get();
      } catch (const EvaluationCancelled&) {
        cancelled_ = true;
      }
      if (cancelled_ || options_.stop.stop_requested()) {
        cancelled_ = true;
        drain();
        break;
      }
      take(f.runs, outcomes);
      if (leaving_) continue;  // the runs in flight count against the budget; nothing more
      leaving_ = leave_ && !fine_phase_ &&
                 int(history_.size()) >= reach_probe_runs(c_.max_evaluations) &&
                 leave_(ratio(), int(history_.size()));
      if (leaving_) continue;
      refit();
      reopen_after_check();
      const Emulators* current =
          fine_phase_ ? (fine_model_ ? &*fine_model_ : nullptr) : (model_ ? &*model_ : nullptr);
      if (current && !checked_) {
        converged_ = shares_below(*current, kShareStop);
        note_answer(*current, int(f.runs.size()));
      }
      while (flights_.size() < 2 && can_plan()) plan_next();
    }
    report.history = history_;
    if (leaving_ && !cancelled_) {
      report.stop_reason = StopReason::converged;
      return;
    }
    report.stop_reason = cancelled_   ? StopReason::cancelled
                         : answered_  ? StopReason::answered
                         : converged_ ? StopReason::converged
                                      : StopReason::budget_exhausted;
    if (fine_model_) {
      report.posterior = summarise(*fine_model_, fine_c_, rounds_);
    } else if (model_) {
      report.posterior = summarise(*model_, c_, rounds_);
      if (has_fine_) report.posterior->resolution = "coarse";
    }
    if (!check_.empty()) {
      report.best = check_record();
      // Against the prediction made before they ran: the posterior above has been fitted on them
      // too, which would pull its prediction toward them.
      if (report.posterior && before_check_) {
        report.posterior->checked_at = before_check_->estimate;
        if (!report.best->loads)
          report.posterior->check_failed =
              report.best->error.empty() ? "no check run reported a result" : report.best->error;
      }
      if (report.posterior && before_check_ && report.best->uct && report.best->btt) {
        report.posterior->uct.check = check_agreement(before_check_->uct, *report.best->uct);
        report.posterior->btt.check = check_agreement(before_check_->btt, *report.best->btt);
      }
    }
    // A region too wide to call unique: which further test would cut it most (on the specimen
    // searched; with a fine specimen the further tests would need fine runs of their own, which
    // this does not design).
    if (report.posterior && !report.posterior->unique && c_.suggest && !has_fine_ && !cancelled_ &&
        !options_.stop.stop_requested()) {
      try {
        report.suggestion = next_test(*model_, history_, c_, evaluator_, batch_);
      } catch (const EvaluationCancelled&) {
        report.stop_reason = StopReason::cancelled;
      } catch (const std::runtime_error&) {
        // An emulator of a further test that cannot be fitted (too few moduli): no suggestion.
      }
    }
  }

 private:
  // Counts the runs over which the current posterior has answered (unique, loads within the
  // tolerance); past kAnsweredRuns the search ends with its check batch.
  void note_answer(const Emulators& m, int runs_taken) {
    const CalibrationCampaign& c = fine_phase_ ? fine_c_ : c_;
    answered_runs_ = shares_below(m, kAnswerShare) && answers(summarise(m, c, rounds_))
                         ? answered_runs_ + runs_taken
                         : 0;
    if (answered_runs_ >= kAnsweredRuns) {
      answered_ = true;
      converged_ = true;
    }
  }

  // Unique, with every predicted load within the tolerance.
  bool answers(const PosteriorSummary& p) const {
    bool met = p.unique && std::abs(p.uct.relative_error) <= c_.tolerance &&
               std::abs(p.btt.relative_error) <= c_.tolerance;
    for (const PredictedLoad& f : p.further)
      met = met && std::abs(f.relative_error) <= c_.tolerance;
    return met;
  }

  // The search stopped before its budget (its posterior answered, or the emulators held too little
  // of its variance for more runs to matter) and checked the estimate. When the check runs
  // disagree with the prediction made before them (the emulators were wrong there), or, after an
  // answer, the posterior fitted on them no longer answers, and budget is left for a batch and
  // another check, the search goes on instead of ending with the question open and runs unspent;
  // the earlier checks stay in the emulators, the next check is at the new estimate.
  void reopen_after_check() {
    if (!checked_ || !converged_ || fine_phase_ || has_fine_ || !model_ || !flights_.empty())
      return;
    if (c_.max_evaluations - launched_ < 2 * batch_ || !before_check_) return;
    const EvaluationRecord check = check_record();
    bool agree = true;
    for (const auto& [predicted, ran] :
         {std::pair{&before_check_->uct, &check.uct}, std::pair{&before_check_->btt, &check.btt}}) {
      if (!*ran) continue;
      const std::optional<CheckAgreement> a = check_agreement(*predicted, **ran);
      agree = agree && (!a || a->agrees);
    }
    if (agree && check.loads && (!answered_ || answers(summarise(*model_, c_, rounds_)))) return;
    checked_ = answered_ = converged_ = false;
    answered_runs_ = 0;
    check_.clear();
    before_check_.reset();
  }

  std::vector<Run> start() {
    const int n = std::min(c_.max_evaluations, std::max(8, 2 * batch_));
    std::vector<Run> runs;
    for (const auto& u : latin_hypercube(n, c_.random_seed)) {
      runs.push_back(run_at(from_unit({u[0], u[1]}, c_), "start"));
    }
    return runs;
  }

  Run run_at(const BondPoint& p, const char* phase, bool fine = false) {
    // Every run a packing of its own (independent scatter); one specimen when seeds do not matter.
    const std::uint64_t seed =
        c_.seed_matters ? c_.sample_seed + std::uint64_t(next_run_) : c_.sample_seed;
    ++next_run_;
    return {p, seed, phase, fine};
  }

  void launch(std::vector<Run> runs) {
    if (runs.empty()) return;
    Evaluator* e = &evaluator_;
    if (runs.front().fine) {
      fine_launched_ += int(runs.size());
      // A fine run is the fine specimen's UCT and BTT: two probes of the evaluator.
      std::vector<ProbeRequest> probes;
      for (const Run& r : runs) {
        probes.push_back({r.point, r.seed, 1, TestKind::uct, c_.fine_patch});
        probes.push_back({r.point, r.seed, 1, TestKind::btt, c_.fine_patch});
      }
      auto work = [e, probes = std::move(probes)] {
        const std::vector<orch::Ensemble> ens = e->probe_batch(probes);
        Batch out;
        for (std::size_t i = 0; i + 1 < probes.size(); i += 2) {
          if (i + 1 < ens.size()) {
            out.outcomes.push_back(outcome_of(ens[i], ens[i + 1]));
          } else {
            out.outcomes.push_back({std::nullopt, "the evaluator runs no fine specimen", {}, {}});
          }
        }
        return out;
      };
      flights_.push_back({std::move(runs), std::async(std::launch::async, std::move(work))});
      return;
    }
    launched_ += int(runs.size());
    std::vector<EvaluationRequest> requests;
    std::vector<ProbeRequest> probes;  // each run's further tests, side by side with its UCT, BTT
    for (const Run& r : runs) {
      requests.push_back({r.point, r.seed, 1, r.phase});
      for (const FurtherTarget& t : c_.further)
        probes.push_back({r.point, r.seed, 1, t.test, t.patch});
    }
    const std::size_t per_run = c_.further.size();
    auto work = [e, per_run, requests = std::move(requests), probes = std::move(probes)] {
      std::future<std::vector<orch::Ensemble>> further;
      if (!probes.empty())
        further = std::async(std::launch::async, [e, &probes] { return e->probe_batch(probes); });
      Batch out;
      out.outcomes = e->evaluate_batch(requests);
      const std::vector<orch::Ensemble> ens =
          further.valid() ? further.get() : std::vector<orch::Ensemble>();
      for (std::size_t i = 0; i < requests.size(); ++i) {
        out.further.emplace_back();
        for (std::size_t k = 0; k < per_run; ++k) {
          const std::size_t at = i * per_run + k;
          out.further.back().push_back(at < ens.size() ? ens[at].peak_load.mean : std::nullopt);
        }
      }
      return out;
    };
    flights_.push_back({std::move(runs), std::async(std::launch::async, std::move(work))});
  }

  void drain() {
    for (Flight& f : flights_) {
      try {
        f.outcomes.get();
      } catch (...) {
      }
    }
    flights_.clear();
  }

  void take(const std::vector<Run>& runs, const Batch& batch) {
    const std::vector<EvaluationOutcome>& outcomes = batch.outcomes;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      EvaluationRecord r;
      r.index = int(history_.size());
      r.phase = runs[i].phase;
      r.point = runs[i].point;
      r.sample_seed = runs[i].seed;
      EvaluationOutcome missing;
      missing.error = "the evaluator returned no outcome";
      if (!fill_record(r, i < outcomes.size() ? outcomes[i] : missing, c_)) {
        r.misfit = failure_floor(c_);
      }
      if (i < batch.further.size()) r.further_n = batch.further[i];
      history_.push_back(r);
      (runs[i].fine ? fine_history_ : coarse_history_).push_back(r);
      if (r.phase == "check" || r.phase == "fine check") check_.push_back(r);
      if (options_.on_evaluation) options_.on_evaluation(r);
    }
  }

  void refit() {
    if (int(coarse_history_.size()) != coarse_fitted_) {
      coarse_fitted_ = int(coarse_history_.size());
      try {
        model_ = fit_emulators(coarse_history_, c_);
      } catch (const std::exception&) {
        model_.reset();  // too few or degenerate runs: the next batch fills the box instead
      }
    }
    if (!fine_phase_ || !model_) return;
    try {
      fine_model_ = fit_fine_emulators(fine_history_, *model_, fine_c_);
    } catch (const std::exception&) {
      fine_model_.reset();  // fewer than 2 fine points: the coarse posterior places the next
    }
  }

  bool can_plan() const {
    if (checked_ || leaving_) return false;
    if (fine_phase_) return fine_launched_ < c_.fine_runs && !fine_in_flight();
    return launched_ < c_.max_evaluations || (has_fine_ && model_);
  }

  void plan_next() {
    if (fine_phase_) return plan_fine();
    const int left = c_.max_evaluations - launched_;
    // With a fine specimen the whole coarse budget goes to the search; its check is fine.
    if (model_ && (converged_ || left <= (has_fine_ ? 0 : batch_))) {
      if (has_fine_) {
        fine_phase_ = true;
        converged_ = answered_ = false;
        answered_runs_ = 0;
        return plan_fine();
      }
      // The check batch: the estimate on `batch` packings (fewer when seeds do not matter).
      before_check_ = summarise(*model_, c_, rounds_);
      const BondPoint estimate = before_check_->estimate;
      std::vector<Run> runs;
      const int n = c_.seed_matters ? std::min(batch_, left) : 1;
      for (int k = 0; k < n; ++k) runs.push_back(run_at(estimate, "check"));
      checked_ = true;
      launch(std::move(runs));
      return;
    }
    ++rounds_;
    launch(model_ ? design(*model_, c_, std::min(batch_, left), false)
                  : space_filling(std::min(batch_, left), c_, false));
  }

  // The fine runs: one batch at a time (a batch planned while another runs would be designed on
  // the same emulators, at the same place), near the current estimate (before two fine points
  // have both loads, the coarse one, weighed by the fine runs' outcomes so that a batch that
  // found no fine peak does not send the next one to the same place), then the check batch at
  // the fine estimate.
  void plan_fine() {
    const int left = c_.fine_runs - fine_launched_;
    if (left <= 0 || fine_in_flight()) return;
    if (fine_model_ && (converged_ || left <= batch_)) {
      before_check_ = summarise(*fine_model_, fine_c_, rounds_);
      const BondPoint estimate = before_check_->estimate;
      std::vector<Run> runs;
      const int n = c_.seed_matters ? std::min(batch_, left) : 1;
      for (int k = 0; k < n; ++k) runs.push_back(run_at(estimate, "fine check", true));
      checked_ = true;
      launch(std::move(runs));
      return;
    }
    ++rounds_;
    const int n = std::min(batch_, left);
    if (!fine_model_ && !model_) return launch(space_filling(n, fine_c_, true));
    const Emulators m =
        fine_model_ ? *fine_model_ : with_fine_outcomes(*model_, fine_history_, fine_c_);
    const Eigen::Vector2d estimate = inference::density_peak(m.grid, m.emulators(), m.targets);
    launch(design(m, fine_c_, n, true, &estimate, !fine_model_));
  }

  bool fine_in_flight() const {
    return std::any_of(flights_.begin(), flights_.end(),
                       [](const Flight& f) { return !f.runs.empty() && f.runs.front().fine; });
  }

  std::vector<Run> space_filling(int n, const CalibrationCampaign& c, bool fine) {
    std::vector<Run> runs;
    for (const auto& u : latin_hypercube(n, c_.random_seed + 7919 * std::uint64_t(rounds_))) {
      runs.push_back(run_at(from_unit({u[0], u[1]}, c), fine ? "fine" : "design", fine));
    }
    return runs;
  }

  // A batch of n runs chosen on emulators m over campaign c's box (the fine campaign's for fine
  // runs; with the coarse emulators there when no fine one is fitted yet, the unit box being
  // shared). Only runs of the same resolution in flight count as pending. With `near` (unit box),
  // only candidates within kFineReach of it, the point itself among them. `distinct`: n points
  // that differ from each other and from the fine points run (the fine emulators need two).
  std::vector<Run> design(const Emulators& m, const CalibrationCampaign& c, int n, bool fine,
                          const Eigen::Vector2d* near = nullptr, bool distinct = false) {
    // Candidates: spread over the box, at the posterior's densest cells, and (when another
    // packing is another specimen) the points already run: a further realisation there.
    std::vector<Eigen::Vector2d> cand;
    std::vector<std::optional<BondPoint>> exact;  // the existing point a candidate repeats
    auto add = [&](const Eigen::Vector2d& u, std::optional<BondPoint> p) {
      if (near && (u - *near).norm() > kFineReach) return false;
      if (distinct &&
          std::any_of(fine_history_.begin(), fine_history_.end(), [&](const EvaluationRecord& r) {
            return (to_unit(r.point, c) - u).norm() < 1e-9;
          }))
        return false;
      cand.push_back(u);
      exact.push_back(p);
      return true;
    };
    if (near) add(*near, std::nullopt);
    const int spread = near ? 0 : kSpaceFilling;
    for (const auto& u :
         latin_hypercube(spread, c_.random_seed + 104729 * std::uint64_t(rounds_))) {
      add({u[0], u[1]}, std::nullopt);
    }
    const std::vector<int> dense =
        inference::densest_cells(m.grid, near ? int(m.grid.weight.size()) : kDensest);
    int densest = 0;
    for (int cell : dense) {
      if (densest == kDensest) break;
      if (add(m.grid.points.row(cell).transpose(), std::nullopt)) ++densest;
    }
    if (c_.seed_matters && (m.coarse_runs > 0) == fine) {
      for (const BondPoint& p : m.points) add(to_unit(p, c), p);
    }
    if (cand.empty()) return space_filling(n, c, fine);
    inference::DesignInput in;
    in.emulators = m.emulators();
    in.targets = m.targets;
    in.posterior = &m.grid;
    in.candidates.resize(Eigen::Index(cand.size()), 2);
    for (std::size_t i = 0; i < cand.size(); ++i) in.candidates.row(Eigen::Index(i)) = cand[i];
    std::vector<Eigen::Vector2d> pend;
    for (const Flight& f : flights_) {
      for (const Run& r : f.runs) {
        if (r.fine == fine) pend.push_back(to_unit(r.point, c));
      }
    }
    in.pending.resize(Eigen::Index(pend.size()), 2);
    for (std::size_t i = 0; i < pend.size(); ++i) in.pending.row(Eigen::Index(i)) = pend[i];
    in.batch = n;
    in.distinct = distinct;
    std::vector<Run> runs;
    std::vector<BondPoint> chosen;
    for (const inference::DesignChoice& d : inference::choose_batch(in)) {
      const BondPoint p =
          exact[d.candidate] ? *exact[d.candidate] : from_unit(cand[d.candidate], c);
      if (!c_.seed_matters && std::find(chosen.begin(), chosen.end(), p) != chosen.end()) continue;
      chosen.push_back(p);
      runs.push_back(run_at(p, fine ? "fine" : "design", fine));
    }
    return runs;
  }

  // The check runs as one ensemble: the estimate's loads over its packings.
  EvaluationRecord check_record() const {
    std::vector<orch::Realisation> uct, btt;
    for (const EvaluationRecord& r : check_) {
      if (r.uct) uct.insert(uct.end(), r.uct->realisations.begin(), r.uct->realisations.end());
      if (r.btt) btt.insert(btt.end(), r.btt->realisations.begin(), r.btt->realisations.end());
    }
    EvaluationRecord best;
    best.index = check_.front().index;
    best.phase = "check";
    best.point = check_.front().point;
    best.sample_seed = check_.front().sample_seed;
    if (uct.empty() || btt.empty() ||
        !fill_record(best, outcome_of(orch::make_ensemble(uct), orch::make_ensemble(btt)), c_)) {
      best.misfit = failure_floor(c_);
    }
    return best;
  }

  const CalibrationCampaign& c_;
  Evaluator& evaluator_;
  const RunOptions& options_;
  const LeaveRange& leave_;
  bool leaving_ = false;  // the runs so far send the calibration on to the next range
  const bool has_fine_;
  CalibrationCampaign fine_c_;  // the fine specimen's view (fine_campaign), when there is one
  bool fine_phase_ = false;
  int fine_launched_ = 0;
  int coarse_fitted_ = -1;  // coarse runs the coarse emulators were last fitted to
  int batch_ = 2;
  int launched_ = 0;
  int next_run_ = 0;
  int rounds_ = 0;
  bool cancelled_ = false, converged_ = false, checked_ = false;
  bool answered_ = false;  // converged_ because the posterior answered (note_answer)
  int answered_runs_ = 0;
  std::deque<Flight> flights_;
  std::vector<EvaluationRecord> history_;  // every run, in the order taken (the report's)
  std::vector<EvaluationRecord> coarse_history_, fine_history_;
  std::vector<EvaluationRecord> check_;
  std::optional<PosteriorSummary> before_check_;  // when the check batch was planned
  std::optional<Emulators> model_, fine_model_;
};

}  // namespace

bool bayes_calibration(const CalibrationCampaign& campaign, Evaluator& evaluator,
                       const RunOptions& options, CalibrationReport& report,
                       const LeaveRange& leave) {
  report.strategy_used = "bayes";
  Search search(campaign, evaluator, options, leave);
  search.run(report);
  report.ratio = search.ratio();
  if (search.left()) return true;  // the driver moves on to the next range
  judge_posterior(report, campaign);
  return false;
}

}  // namespace rockcal::calibration
