// A calibration's progress: one model that the live summary and the final report carry and every
// reader shows as it is (the CLI's progress line and summary, the dashboard's bar and verdict).
#pragma once

#include <cstddef>
#include <optional>

#include <nlohmann/json.hpp>

#include "orchestrator/calibration/campaign.hpp"

namespace rockcal::calibration {

// The packings the best point is re-run on once the search has ended (its own seed is not).
int seed_reruns(const CalibrationCampaign& c);

// How fast the evaluations go: seconds per search evaluation and per fine run (a fine specimen's
// UCT and BTT), each measured on its own kind (unset until one has been timed), and the fine runs
// done so far.
struct EvaluationPace {
  std::optional<double> search;
  std::optional<double> fine;
  int fine_done = 0;
};

// What a fine run costs against a search evaluation, before one has been timed: particles times
// steps, (D_f / D)^2 (H_f / H)^2 (r / r_f)^4 (the count as D^2 H / r^3, the steps as the height
// the platens travel over the time step, which goes with the radius). Unset when the template does
// not give the sample's diameter, height and radius.
std::optional<double> fine_cost_ratio(const CalibrationCampaign& c);

// The campaign progress model (orchestrator/progress_model.hpp) in "evaluations": done of the
// whole budget (the search's max_evaluations and the consistent-set trace's
// consistency_evaluations, parts "search" and "valley trace"; the bayes strategy's "fine runs"),
// with the best point's seed re-runs beside it ("seed_reruns", counted in what is left) and the
// seconds left: each part's evaluations left at its own pace (the fine runs' before one has been
// timed at the search's times fine_cost_ratio; none when that is unknown).
nlohmann::json progress_model_json(std::size_t evaluations, const CalibrationCampaign& c,
                                   const EvaluationPace& pace, bool finished);

}  // namespace rockcal::calibration
