// Strict reading of one JSON object of a campaign: typed getters that name the field on error,
// and a final check that no key was left unread (a typo must not silently fall back to a default).
// The one reader of request JSON: campaigns of every kind, datasets and twin requests use it, and
// every refusal is a RequestError naming the dotted path of the field.
#pragma once

#include <cstdint>
#include <optional>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

namespace rockcal::orch {

class JsonFields {
 public:
  JsonFields(const nlohmann::json& object, std::string path);

  std::string path_of(const std::string& key) const;
  const nlohmann::json* get(const std::string& key);
  const nlohmann::json& require(const std::string& key);

  std::optional<double> number(const std::string& key);
  std::optional<double> positive(const std::string& key);
  double required_positive(const std::string& key);  // "is required" when absent
  std::optional<std::int64_t> integer(const std::string& key, std::int64_t lo, std::int64_t hi);
  std::optional<std::string> string(const std::string& key);
  std::optional<bool> boolean(const std::string& key);

  void reject_unknown() const;

 private:
  const nlohmann::json& object_;
  std::string path_;
  std::set<std::string> read_;
};

// A finite JSON number, or RequestError naming `field`.
double finite_number(const nlohmann::json& value, const std::string& field);

}  // namespace rockcal::orch
