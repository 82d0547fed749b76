#include "orchestrator/calibration/ledger.hpp"

#include <algorithm>
#include <cmath>

#include "orchestrator/calibration/search_space.hpp"

namespace rockcal::calibration {

Ledger::Ledger(const CalibrationCampaign& campaign, Evaluator& evaluator, std::stop_token stop,
               RecordCallback on_record)
    : campaign_(campaign),
      evaluator_(evaluator),
      stop_(stop),
      on_record_(std::move(on_record)),
      budget_(campaign.max_evaluations) {}

void Ledger::extend_beyond_target(int evaluations) {
  budget_ = int(history_.size()) + std::max(0, evaluations);
  stop_at_target_ = false;
}

std::vector<EvaluationRecord> Ledger::evaluate(const std::vector<BondPoint>& points,
                                               const std::string& phase) {
  if (stop_.stop_requested()) throw EvaluationCancelled();
  std::vector<BondPoint> clipped;
  std::vector<BondPoint> fresh;
  for (const BondPoint& p : points) {
    clipped.push_back(clip_to_bounds(p, campaign_));
    const bool known = index_of_point_.count({clipped.back().fr0_n, clipped.back().fs0_n}) ||
                       std::find(fresh.begin(), fresh.end(), clipped.back()) != fresh.end();
    if (!known) fresh.push_back(clipped.back());
  }
  const bool truncated = int(fresh.size()) > remaining();
  if (truncated) fresh.resize(std::max(0, remaining()));
  if (!fresh.empty()) {
    std::vector<EvaluationRequest> requests;
    for (const BondPoint& p : fresh) {
      requests.push_back({p, campaign_.sample_seed, campaign_.realisations});
    }
    const std::vector<EvaluationOutcome> outcomes = evaluator_.evaluate_batch(requests);
    for (std::size_t i = 0; i < fresh.size(); ++i) {
      EvaluationOutcome missing;
      missing.error = "the evaluator returned no outcome";
      history_.push_back(record(fresh[i], i < outcomes.size() ? outcomes[i] : missing, phase));
      index_of_point_[{fresh[i].fr0_n, fresh[i].fs0_n}] = history_.back().index;
      if (on_record_) on_record_(history_.back());
    }
  }
  if (truncated || (stop_at_target_ && target_met())) throw SearchDone{};
  std::vector<EvaluationRecord> records;
  for (const BondPoint& p : clipped)
    records.push_back(history_[index_of_point_.at({p.fr0_n, p.fs0_n})]);
  return records;
}

EvaluationRecord Ledger::evaluate_one(const BondPoint& point, const std::string& phase) {
  return evaluate({point}, phase).front();
}

bool fill_record(EvaluationRecord& r, const EvaluationOutcome& outcome,
                 const CalibrationCampaign& campaign) {
  r.error = outcome.error;
  r.uct = outcome.uct;
  r.btt = outcome.btt;
  // A zero or non-finite peak load has no log-ratio: it is a failed run, not a data point.
  const bool usable = outcome.loads && std::isfinite(outcome.loads->uct_n) &&
                      std::isfinite(outcome.loads->btt_n) && outcome.loads->uct_n > 0 &&
                      outcome.loads->btt_n > 0;
  if (!usable) {
    if (outcome.loads) r.error = "non-positive or non-finite peak load";
    if (r.error.empty()) r.error = "evaluation failed";
    return false;
  }
  const PeakLoads& targets = campaign.targets.model_loads_n;
  r.loads = outcome.loads;
  r.rel_se = {outcome.uct ? orch::relative_se(outcome.uct->peak_load) : 0.0,
              outcome.btt ? orch::relative_se(outcome.btt->peak_load) : 0.0};
  r.misfit = misfit(log_errors(*r.loads, targets), {campaign.weight_uct, campaign.weight_btt});
  r.within_tolerance = within_tolerance(*r.loads, targets, campaign.tolerance, r.rel_se);
  return true;
}

double failure_floor(const CalibrationCampaign& c) {
  return (c.weight_uct + c.weight_btt) * std::pow(std::log(10.0), 2);
}

EvaluationRecord Ledger::record(const BondPoint& point, const EvaluationOutcome& outcome,
                                const std::string& phase) {
  EvaluationRecord r;
  r.index = int(history_.size());
  r.phase = phase;
  r.point = point;
  r.sample_seed = campaign_.sample_seed;
  if (!fill_record(r, outcome, campaign_)) r.misfit = failure_penalty(point);
  return r;
}

// NLopt cannot handle NaN, so a failure gets a finite penalty: twice the worst misfit among the
// three successful evaluations nearest to it (in the log box). The optimiser steps away from it,
// but the penalty stays on the scale of its neighbourhood: a global "worst ever" penalty next to
// the optimum wrecks BOBYQA's quadratic model and stalls it there.
double Ledger::failure_penalty(const BondPoint& point) const {
  const double floor = failure_floor(campaign_);
  const double du = std::log(campaign_.fr0_n.hi / campaign_.fr0_n.lo);
  const double dv = std::log(campaign_.fs0_n.hi / campaign_.fs0_n.lo);
  std::vector<std::pair<double, double>> by_distance;  // (distance, misfit)
  for (const EvaluationRecord& r : history_) {
    if (!r.loads) continue;
    const double a = std::log(r.point.fr0_n / point.fr0_n) / du;
    const double b = std::log(r.point.fs0_n / point.fs0_n) / dv;
    by_distance.push_back({a * a + b * b, r.misfit});
  }
  if (by_distance.empty()) return floor;
  const std::size_t k = std::min<std::size_t>(3, by_distance.size());
  std::partial_sort(by_distance.begin(), by_distance.begin() + k, by_distance.end());
  double worst = 0.0;
  for (std::size_t i = 0; i < k; ++i) worst = std::max(worst, by_distance[i].second);
  return 2.0 * worst;
}

// A point that meets both tolerances beats one with a lower misfit that does not (one load 0%
// off, the other 2.5%); among equals, the lower misfit.
const EvaluationRecord* Ledger::best() const {
  const EvaluationRecord* best = nullptr;
  for (const EvaluationRecord& r : history_) {
    if (!r.loads) continue;
    if (!best || std::pair(!r.within_tolerance, r.misfit) <
                     std::pair(!best->within_tolerance, best->misfit)) {
      best = &r;
    }
  }
  return best;
}

bool Ledger::target_met() const {
  return std::any_of(history_.begin(), history_.end(),
                     [](const EvaluationRecord& r) { return r.within_tolerance; });
}

}  // namespace rockcal::calibration
