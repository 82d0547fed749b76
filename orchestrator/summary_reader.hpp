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

}  // namespace rockcal::summary
