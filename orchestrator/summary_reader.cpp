#include "orchestrator/summary_reader.hpp"

#include <cstdio>
#include <sstream>
#include <vector>

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

std::string budget_count(const nlohmann::json& model, const std::string& suffix) {
  std::ostringstream out;
  out << at(model, "done") << " of " << at(model, "budget") << suffix;
  std::vector<std::string> notes;
  const nlohmann::json& parts = at(model, "parts");
  if (parts.is_array() && parts.size() > 1) {
    std::string list;
    for (const nlohmann::json& p : parts) {
      // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on ", " + std::string.
      if (!list.empty()) list += ", ";
      list += p["name"].get<std::string>();
      list += ' ';
      list += p["budget"].dump();
    }
    notes.push_back(list);
  }
  if (at(model, "seed_reruns").is_number() && model["seed_reruns"].get<int>() > 0) {
    std::string reruns = "+";
    reruns += model["seed_reruns"].dump();
    reruns += " seed re-runs";
    notes.push_back(reruns);
  }
  for (std::size_t k = 0; k < notes.size(); ++k) out << (k ? "; " : " (") << notes[k];
  if (!notes.empty()) out << ")";
  return out.str();
}

}  // namespace rockcal::summary
