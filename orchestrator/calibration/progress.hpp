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

// {"unit": "evaluations", "done", "budget", "parts": [{"name": "search" | "valley trace",
//  "budget"}], "seed_reruns", "left", "fraction", "eta_seconds"}: evaluations done of the whole
// budget (the search's max_evaluations and the consistent-set trace's consistency_evaluations,
// each part named), the best point's seed re-runs beside it, what is left (budget - done, at
// least 0, plus the re-runs; 0 once finished), the fraction done (never backwards: evaluations
// only grow against a fixed budget; 1 once finished) and the seconds left at the measured pace
// (null until an evaluation has been timed and when nothing is left; at least 1 while something
// is).
nlohmann::json progress_model_json(std::size_t evaluations, const CalibrationCampaign& c,
                                   std::optional<double> seconds_per_evaluation, bool finished);

}  // namespace rockcal::calibration
