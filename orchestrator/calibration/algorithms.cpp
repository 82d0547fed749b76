#include "orchestrator/calibration/algorithms.hpp"

#include <utility>

namespace rockcal::calibration {
namespace {

// Derivative-free only: a DEM peak load has no gradient worth the name (bond breakage is discrete).
const std::vector<std::pair<std::string, nlopt::algorithm>>& table() {
  static const std::vector<std::pair<std::string, nlopt::algorithm>> algorithms = {
      {"bobyqa", nlopt::LN_BOBYQA},         {"sbplx", nlopt::LN_SBPLX},
      {"neldermead", nlopt::LN_NELDERMEAD}, {"cobyla", nlopt::LN_COBYLA},
      {"direct_l", nlopt::GN_DIRECT_L},     {"crs2_lm", nlopt::GN_CRS2_LM},
  };
  return algorithms;
}

}  // namespace

std::optional<nlopt::algorithm> nlopt_algorithm(const std::string& name) {
  for (const auto& [known, algorithm] : table()) {
    if (known == name) return algorithm;
  }
  return std::nullopt;
}

std::vector<std::string> algorithm_names() {
  std::vector<std::string> names;
  for (const auto& entry : table()) names.push_back(entry.first);
  return names;
}

}  // namespace rockcal::calibration
