#include "orchestrator/calibration/progress.hpp"

#include <algorithm>
#include <cmath>

namespace rockcal::calibration {

int seed_reruns(const CalibrationCampaign& c) {
  return int(std::count_if(c.scatter_seeds.begin(), c.scatter_seeds.end(),
                           [&](std::uint64_t s) { return s != c.sample_seed; }));
}

nlohmann::json progress_model_json(std::size_t evaluations, const CalibrationCampaign& c,
                                   std::optional<double> seconds_per_evaluation, bool finished) {
  using nlohmann::json;
  // The bayes strategy's fine runs follow its search (the old driver's corrections are not
  // evaluations of the search's kind and stay outside the count).
  const int fine = c.strategy == Strategy::bayes && !c.fine_patch.is_null() ? c.fine_runs : 0;
  const int budget = c.max_evaluations + c.consistency_evaluations + fine;
  json parts = json::array({{{"name", "search"}, {"budget", c.max_evaluations}}});
  if (c.consistency_evaluations > 0)
    parts.push_back({{"name", "valley trace"}, {"budget", c.consistency_evaluations}});
  if (fine > 0) parts.push_back({{"name", "fine runs"}, {"budget", fine}});
  const int done = int(evaluations);
  const int left = finished ? 0 : std::max(0, budget - done) + seed_reruns(c);
  json eta = nullptr;
  if (finished) {
    eta = 0.0;
  } else if (seconds_per_evaluation && left > 0) {
    eta = std::max(1.0, std::ceil(left * *seconds_per_evaluation));
  }
  return {{"unit", "evaluations"},
          {"done", done},
          {"budget", budget},
          {"parts", parts},
          {"seed_reruns", seed_reruns(c)},
          {"left", left},
          {"fraction", finished ? 1.0 : std::min(1.0, double(done) / double(budget))},
          {"eta_seconds", eta}};
}

}  // namespace rockcal::calibration
