// Runs an NLopt minimisation with a C++ objective whose exceptions (SearchDone, cancellation,
// infrastructure errors) must survive NLopt's C core: nlopt.hpp would turn them into a bare
// "nlopt failure". They are stored, NLopt is stopped with forced_stop, and they are rethrown here.
#pragma once

#include <functional>
#include <vector>

#include <nlopt.hpp>

namespace rockcal::calibration {

using NloptObjective = std::function<double(const std::vector<double>& x)>;

// Minimises from x (updated to NLopt's final point). NLopt's own stops (tolerances, maxeval,
// round-off) return normally.
void minimise(nlopt::opt& opt, std::vector<double>& x, NloptObjective objective);

}  // namespace rockcal::calibration
