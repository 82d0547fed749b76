#include "orchestrator/calibration/progress.hpp"

#include <algorithm>

#include "orchestrator/progress_model.hpp"

namespace rockcal::calibration {

int seed_reruns(const CalibrationCampaign& c) {
  return int(std::count_if(c.scatter_seeds.begin(), c.scatter_seeds.end(),
                           [&](std::uint64_t s) { return s != c.sample_seed; }));
}

nlohmann::json progress_model_json(std::size_t evaluations, const CalibrationCampaign& c,
                                   std::optional<double> seconds_per_evaluation, bool finished) {
  // The bayes strategy's fine runs follow its search (the NLopt driver's corrections are not
  // evaluations of the search's kind and stay outside the count).
  const int fine = c.strategy == Strategy::bayes && !c.fine_patch.is_null() ? c.fine_runs : 0;
  std::vector<orch::BudgetPart> parts = {{"search", c.max_evaluations}};
  if (c.consistency_evaluations > 0) parts.push_back({"valley trace", c.consistency_evaluations});
  if (fine > 0) parts.push_back({"fine runs", fine});
  nlohmann::json model = orch::progress_model_json(
      "evaluations", int(evaluations), parts, seed_reruns(c), seconds_per_evaluation, finished);
  model["seed_reruns"] = seed_reruns(c);
  return model;
}

}  // namespace rockcal::calibration
