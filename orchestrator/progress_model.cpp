#include "orchestrator/progress_model.hpp"

#include <algorithm>
#include <cmath>

namespace rockcal::orch {

nlohmann::json progress_model_json(const std::string& unit, int done,
                                   const std::vector<BudgetPart>& parts, int extra_left,
                                   std::optional<double> seconds_per_unit, bool finished) {
  using nlohmann::json;
  int budget = 0;
  json named = json::array();
  for (const BudgetPart& p : parts) {
    budget += p.budget;
    named.push_back({{"name", p.name}, {"budget", p.budget}});
  }
  const int left = finished ? 0 : std::max(0, budget - done) + extra_left;
  json eta = nullptr;
  if (finished) {
    eta = 0.0;
  } else if (seconds_per_unit && left > 0) {
    eta = std::max(1.0, std::ceil(left * *seconds_per_unit));
  }
  const double fraction =
      finished ? 1.0 : (budget > 0 ? std::min(1.0, double(done) / double(budget)) : 0.0);
  return {{"unit", unit}, {"done", done},         {"budget", budget},  {"parts", named},
          {"left", left}, {"fraction", fraction}, {"eta_seconds", eta}};
}

std::vector<BudgetPart> budget_parts(const nlohmann::json& model) {
  std::vector<BudgetPart> out;
  if (!model.is_object() || !model.contains("parts") || !model["parts"].is_array()) return out;
  for (const nlohmann::json& p : model["parts"]) {
    if (p.is_object() && p.value("name", nlohmann::json()).is_string() &&
        p.value("budget", nlohmann::json()).is_number_integer()) {
      out.push_back({p["name"].get<std::string>(), p["budget"].get<int>()});
    }
  }
  return out;
}

}  // namespace rockcal::orch
