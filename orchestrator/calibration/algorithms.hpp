// The NLopt algorithms a campaign may name. Local ones start from the best point so far; global
// ones (DIRECT-L, CRS2) search the whole log box and ignore the start.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlopt.hpp>

namespace rockcal::calibration {

std::optional<nlopt::algorithm> nlopt_algorithm(const std::string& name);
std::vector<std::string> algorithm_names();

}  // namespace rockcal::calibration
