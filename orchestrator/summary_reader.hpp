// Reading a stored campaign summary (a calibration's or a diagnosis's report) for text a person
// reads: the CLI's tables and the diagnosis's HTML page share these.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace rockcal::summary {

// j[key] when j is an object that has it, else null: a summary's optional fields.
const nlohmann::json& at(const nlohmann::json& j, const char* key);

// `x` in a printf format for one double ("%.4g", "%+.2f%%").
std::string printed(double x, const char* format = "%.4g");

// "3 of 64<suffix> (search 40, valley trace 24; +2 seed re-runs)": a progress model's count
// (orchestrator/progress_model.hpp), each part of its budget named.
std::string budget_count(const nlohmann::json& model, const std::string& suffix);

}  // namespace rockcal::summary
