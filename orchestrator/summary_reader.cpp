#include "orchestrator/summary_reader.hpp"

#include <cstdio>

namespace rockcal::summary {

const nlohmann::json& at(const nlohmann::json& j, const char* key) {
  static const nlohmann::json null;
  return j.is_object() && j.contains(key) ? j[key] : null;
}

std::string printed(double x, const char* format) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, x);
  return buffer;
}

}  // namespace rockcal::summary
