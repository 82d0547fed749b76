#include "orchestrator/json_fields.hpp"

#include <cmath>

#include "orchestrator/request_error.hpp"

namespace rockcal::orch {

JsonFields::JsonFields(const nlohmann::json& object, std::string path)
    : object_(object), path_(std::move(path)) {
  if (!object_.is_object()) {
    throw RequestError(path_.empty() ? "(root)" : path_, "must be a JSON object");
  }
}

std::string JsonFields::path_of(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

const nlohmann::json* JsonFields::get(const std::string& key) {
  read_.insert(key);
  auto it = object_.find(key);
  return it == object_.end() ? nullptr : &*it;
}

const nlohmann::json& JsonFields::require(const std::string& key) {
  const nlohmann::json* v = get(key);
  if (!v) throw RequestError(path_of(key), "is required");
  return *v;
}

double finite_number(const nlohmann::json& value, const std::string& field) {
  if (!value.is_number()) throw RequestError(field, "must be a number");
  const double x = value.get<double>();
  if (!std::isfinite(x)) throw RequestError(field, "must be finite");
  return x;
}

std::optional<double> JsonFields::number(const std::string& key) {
  const nlohmann::json* v = get(key);
  if (!v) return std::nullopt;
  return finite_number(*v, path_of(key));
}

std::optional<double> JsonFields::positive(const std::string& key) {
  auto x = number(key);
  if (x && !(*x > 0)) throw RequestError(path_of(key), "must be positive");
  return x;
}

double JsonFields::required_positive(const std::string& key) {
  const auto x = positive(key);
  if (!x) throw RequestError(path_of(key), "is required");
  return *x;
}

std::optional<std::int64_t> JsonFields::integer(const std::string& key, std::int64_t lo,
                                                std::int64_t hi) {
  const nlohmann::json* v = get(key);
  if (!v) return std::nullopt;
  const bool fits = v->is_number_integer() &&
                    !(v->is_number_unsigned() && v->get<std::uint64_t>() > std::uint64_t(hi));
  // Built by appending: GCC 12 warns falsely (-Wrestrict) on "[" + std::to_string(...).
  std::string range = "[";
  range.append(std::to_string(lo)).append(", ").append(std::to_string(hi)).append("]");
  if (!fits) throw RequestError(path_of(key), "must be an integer in " + range);
  const std::int64_t x = v->get<std::int64_t>();
  if (x < lo || x > hi) throw RequestError(path_of(key), "must be in " + range);
  return x;
}

std::optional<std::string> JsonFields::string(const std::string& key) {
  const nlohmann::json* v = get(key);
  if (!v) return std::nullopt;
  if (!v->is_string()) throw RequestError(path_of(key), "must be a string");
  return v->get<std::string>();
}

std::optional<bool> JsonFields::boolean(const std::string& key) {
  const nlohmann::json* v = get(key);
  if (!v) return std::nullopt;
  if (!v->is_boolean()) throw RequestError(path_of(key), "must be true or false");
  return v->get<bool>();
}

void JsonFields::reject_unknown() const {
  for (auto it = object_.begin(); it != object_.end(); ++it) {
    if (!read_.count(it.key())) throw RequestError(path_of(it.key()), "unknown field");
  }
}

}  // namespace rockcal::orch
