#include "orchestrator/calibration/progress.hpp"

#include <algorithm>
#include <cmath>

#include "orchestrator/progress_model.hpp"

namespace rockcal::calibration {

int seed_reruns(const CalibrationCampaign& c) {
  return int(std::count_if(c.scatter_seeds.begin(), c.scatter_seeds.end(),
                           [&](std::uint64_t s) { return s != c.sample_seed; }));
}

std::optional<double> fine_cost_ratio(const CalibrationCampaign& c) {
  if (c.fine_patch.is_null()) return std::nullopt;
  nlohmann::json fine = c.job_template;
  fine.merge_patch(c.fine_patch);
  const nlohmann::json coarse_sample = c.job_template.value("sample", nlohmann::json::object());
  const nlohmann::json fine_sample = fine.value("sample", nlohmann::json::object());
  double ratio = 1.0;
  // field, the power of fine/coarse it enters with
  for (const auto& [field, power] :
       {std::pair{"diameter", 2.0}, std::pair{"height", 2.0}, std::pair{"radius", -4.0}}) {
    const nlohmann::json x = coarse_sample.value(field, nlohmann::json());
    const nlohmann::json y = fine_sample.value(field, nlohmann::json());
    if (!x.is_number() || !y.is_number() || x.get<double>() <= 0 || y.get<double>() <= 0)
      return std::nullopt;
    ratio *= std::pow(y.get<double>() / x.get<double>(), power);
  }
  return ratio;
}

nlohmann::json progress_model_json(std::size_t evaluations, const CalibrationCampaign& c,
                                   const EvaluationPace& pace, bool finished) {
  // The bayes strategy's fine runs follow its search (the NLopt driver's corrections are not
  // evaluations of the search's kind and stay outside the count).
  const int fine = c.strategy == Strategy::bayes && !c.fine_patch.is_null() ? c.fine_runs : 0;
  std::vector<orch::BudgetPart> parts = {{"search", c.max_evaluations}};
  if (c.consistency_evaluations > 0) parts.push_back({"valley trace", c.consistency_evaluations});
  if (fine > 0) parts.push_back({"fine runs", fine});
  nlohmann::json model = orch::progress_model_json("evaluations", int(evaluations), parts,
                                                   seed_reruns(c), pace.search, finished);
  model["seed_reruns"] = seed_reruns(c);
  if (fine > 0 && !finished) {
    // The search's evaluations and the fine runs left, each at its own pace. A search that ends
    // early (answered) leaves its budget unspent and goes on to the fine runs.
    const int fine_left = std::max(0, fine - pace.fine_done);
    const int search_left =
        pace.fine_done > 0 ? 0 : std::max(0, model["left"].get<int>() - fine_left - seed_reruns(c));
    std::optional<double> per_fine = pace.fine;
    const std::optional<double> ratio = fine_cost_ratio(c);
    if (!per_fine && pace.search && ratio) per_fine = *pace.search * *ratio;
    nlohmann::json eta = nullptr;
    if ((search_left == 0 || pace.search) && (fine_left == 0 || per_fine)) {
      const double s = (search_left > 0 ? search_left * *pace.search : 0.0) +
                       (fine_left > 0 ? fine_left * *per_fine : 0.0);
      if (search_left + fine_left > 0) eta = std::max(1.0, std::ceil(s));
    }
    model["eta_seconds"] = eta;
  }
  return model;
}

}  // namespace rockcal::calibration
