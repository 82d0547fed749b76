// A campaign's progress model, one shape for every kind whose driver adds work as it goes (a
// calibration's evaluations, a diagnosis's jobs): what is done of a fixed budget with its parts
// named, what is left, the fraction done and the seconds left. The live summary and the final
// report carry it, and every reader (the CLI's progress line, the dashboard, the HTML report)
// shows it as it is.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rockcal::orch {

// One named part of a budget ("search", "valley trace"; "grid", "budget", "confirm").
struct BudgetPart {
  std::string name;
  int budget = 0;
};

// {"unit", "done", "budget", "parts": [{"name", "budget"}], "left", "fraction", "eta_seconds"}:
// `done` `unit` of the budget (the parts' sum), what is left (budget - done, at least 0, plus
// `extra_left` units outside the budget; 0 once finished), the fraction done (done of a budget
// fixed up front, so it never goes backwards; at most 1, and 1 once finished) and the seconds left
// at `seconds_per_unit` (null until a unit has been timed and when nothing is left; at least 1
// while something is; 0 once finished).
nlohmann::json progress_model_json(const std::string& unit, int done,
                                   const std::vector<BudgetPart>& parts, int extra_left,
                                   std::optional<double> seconds_per_unit, bool finished);

// The parts of a model (progress_model_json's "parts"); empty when it has none.
std::vector<BudgetPart> budget_parts(const nlohmann::json& model);

}  // namespace rockcal::orch
