#include "orchestrator/request_fields.hpp"

#include <algorithm>
#include <cmath>

#include "engine/spec.hpp"
#include "orchestrator/json_fields.hpp"
#include "orchestrator/request_error.hpp"

namespace rockcal::orch {

std::string campaign_name(const nlohmann::json& request, const std::string& fallback) {
  auto it = request.find("name");
  if (it == request.end()) return fallback;
  if (!it->is_string()) throw RequestError("name", "must be a string");
  std::string name = it->get<std::string>();
  if (name.size() > 200) throw RequestError("name", "must be at most 200 characters");
  for (unsigned char ch : name) {
    if (ch < 0x20) throw RequestError("name", "must not contain control characters");
  }
  return name;
}

double positive_number(const nlohmann::json& value, const std::string& field) {
  const double x = finite_number(value, field);
  if (!(x > 0)) throw RequestError(field, "must be positive");
  return x;
}

std::vector<double> positive_numbers(const nlohmann::json& value, const std::string& field,
                                     std::size_t max_size) {
  if (!value.is_array()) throw RequestError(field, "must be an array of numbers");
  if (value.empty()) throw RequestError(field, "must not be empty");
  if (value.size() > max_size) {
    throw RequestError(field, "has " + std::to_string(value.size()) + " values; the cap is " +
                                  std::to_string(max_size));
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < value.size(); ++i) {
    out.push_back(positive_number(value[i], field + "[" + std::to_string(i) + "]"));
  }
  return out;
}

std::vector<std::string> test_names(const nlohmann::json& request) {
  auto it = request.find("tests");
  if (it == request.end()) throw RequestError("tests", "is required (e.g. [\"uct\", \"btt\"])");
  if (!it->is_array() || it->empty()) throw RequestError("tests", "must be a non-empty array");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < it->size(); ++i) {
    std::string field = "tests[" + std::to_string(i) + "]";
    const auto& t = (*it)[i];
    if (!t.is_string()) throw RequestError(field, "must be a string");
    std::string name = t.get<std::string>();
    if (!rockcal::test_kind_from_string(name)) {
      throw RequestError(field, "unknown test '" + name + "' (known: uct, btt, elastic, triaxial)");
    }
    if (std::find(out.begin(), out.end(), name) != out.end()) {
      throw RequestError(field, "duplicate test '" + name + "'");
    }
    out.push_back(name);
  }
  return out;
}

const nlohmann::json& job_template(const nlohmann::json& request) {
  auto it = request.find("job");
  if (it == request.end()) throw RequestError("job", "is required (the job template)");
  if (!it->is_object()) throw RequestError("job", "must be a JSON object");
  if (it->contains("test")) {
    throw RequestError("job.test", "a template must not name the test; \"tests\" does");
  }
  return *it;
}

}  // namespace rockcal::orch
