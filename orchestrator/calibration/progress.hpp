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

// The campaign progress model (orchestrator/progress_model.hpp) in "evaluations": done of the
// whole budget (the search's max_evaluations and the consistent-set trace's
// consistency_evaluations, parts "search" and "valley trace"), with the best point's seed re-runs
// beside it ("seed_reruns", counted in what is left) and the seconds left at the measured pace.
nlohmann::json progress_model_json(std::size_t evaluations, const CalibrationCampaign& c,
                                   std::optional<double> seconds_per_evaluation, bool finished);

}  // namespace rockcal::calibration
