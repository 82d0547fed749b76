// The calibration's two emulators (ln UCT and ln BTT peak load over the unit log box) fitted to a
// campaign's runs, the posterior they give for its targets, and the summary of that posterior.
#pragma once

#include <optional>
#include <vector>

#include "orchestrator/calibration/bayes/summary.hpp"
#include "orchestrator/calibration/ledger.hpp"
#include "orchestrator/inference/posterior/feasibility.hpp"
#include "orchestrator/inference/posterior/posterior.hpp"
#include "orchestrator/ratio_range.hpp"

namespace rockcal::calibration {

struct Emulators {
  inference::Gp uct, btt;
  std::vector<inference::Gp> further;  // one per further target (campaign.further)
  int runs = 0;
  int coarse_runs = 0;  // fine emulators: the coarse runs beneath them (0 for coarse emulators)
  std::vector<BondPoint> points;  // the distinct points run, in first-run order
  // Where runs ended with both loads (1) or a test without a peak (0): the grid's feasibility is
  // from them (inference/posterior/feasibility.hpp); for fine emulators, the fine runs' own and
  // the coarse runs' away from them.
  inference::RunResults outcomes;
  std::vector<inference::Target> targets;
  inference::PosteriorGrid grid;
  std::vector<const inference::Gp*> emulators() const {
    std::vector<const inference::Gp*> all = {&uct, &btt};
    for (const inference::Gp& gp : further) all.push_back(&gp);
    return all;
  }
};

// The targets in ln with the lab's relative sd and the stated discrepancy.
std::vector<inference::Target> inference_targets(const CalibrationCampaign& c);

// Throws std::runtime_error with fewer than 3 distinct successful points (or a failed fit).
Emulators fit_emulators(const std::vector<EvaluationRecord>& history, const CalibrationCampaign& c);

// The fine specimen's emulators: the coarse ones plus a discrepancy fitted to the fine runs
// (inference/emulator/two_level.hpp). `fine_c` is the campaign as the fine specimen sees it
// (fine_campaign): its box is the coarse one scaled, so both share the unit coordinates. Throws
// std::runtime_error with fewer than 2 distinct successful fine points.
Emulators fit_fine_emulators(const std::vector<EvaluationRecord>& fine, const Emulators& coarse,
                             const CalibrationCampaign& fine_c);

// The coarse emulators placing the first fine runs, before two fine points have both loads: their
// posterior weighed by the fine runs' outcomes too (where a fine run had no peak, the fine
// specimen's answer is not, whatever the coarse runs there gave).
Emulators with_fine_outcomes(const Emulators& coarse, const std::vector<EvaluationRecord>& fine,
                             const CalibrationCampaign& fine_c);

// The campaign the fine runs answer: the job template with the fine patch merged in and the
// strength bounds times the fine strength scale.
CalibrationCampaign fine_campaign(const CalibrationCampaign& c);

std::vector<double> emulator_shares(const Emulators& m);

// The posterior's density peak, in model units (the summary's estimate).
BondPoint posterior_estimate(const Emulators& m, const CalibrationCampaign& c);

// Whether p lies in the summary's credible region (one of its cells on the log box).
bool in_credible_region(const PosteriorSummary& s, const BondPoint& p);

PosteriorSummary summarise(const Emulators& m, const CalibrationCampaign& c, int rounds);

// The UCT/BTT load ratios the emulators' means give at the points run whose UCT peaked (their
// packings' scatter smoothed out): sets range's emulated reach.
void set_emulated_reach(const Emulators& m, orch::RatioRange& range);

}  // namespace rockcal::calibration
