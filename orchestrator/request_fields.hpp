// Checks of request values shared by campaign kinds, on top of the field reader (json_fields.hpp);
// each throws RequestError naming the field.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rockcal::orch {

// The campaign name (optional, default `fallback`): a short printable string.
std::string campaign_name(const nlohmann::json& request, const std::string& fallback);

// A positive finite number.
double positive_number(const nlohmann::json& value, const std::string& field);

// A non-empty array of at most `max_size` positive finite numbers.
std::vector<double> positive_numbers(const nlohmann::json& value, const std::string& field,
                                     std::size_t max_size);

// "tests": a non-empty list of distinct test names the engine knows.
std::vector<std::string> test_names(const nlohmann::json& request);

// The job template ("job"): an object without "test" (the campaign names the tests).
const nlohmann::json& job_template(const nlohmann::json& request);

}  // namespace rockcal::orch
