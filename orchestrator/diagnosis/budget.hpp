// The numerical error budget: how much each observation moves when nothing physical changes (other
// packing seeds, half the platen speed, a finer resolution). A residual inside it is not a physics
// gap, and an effect that moves nothing beyond it cannot be told apart from numerical noise.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "orchestrator/diagnosis/evaluator.hpp"

namespace rockcal::diagnosis {

struct BudgetSpec {
  std::vector<std::uint64_t> seeds;  // replicate packing seeds (default: template seed + 1, + 2)
  double speed_factor = 0.5;         // platen speed multiplier
  double resolution = 1.25;          // particles per length multiplier
};

struct BudgetVariant {
  std::string name;  // "seed 2", "speed x0.5", "resolution x1.25"
  Numerics numerics;
};

// The seed replicates first, then the speed and the resolution variants.
std::vector<BudgetVariant> budget_variants(const BudgetSpec& spec, std::uint64_t template_seed);

struct Budget {
  std::vector<BudgetVariant> variants;
  std::vector<std::vector<double>> change;  // [variant][target] |ln(variant / reference)|, NaN
  std::vector<double> per_target;           // the largest change; see numerical_budget
  std::vector<bool> measured;               // false where no variant measured the target
};

// Per target the largest |ln| change over the variants. A target no variant measured (every run
// failed) gets the largest budget of the others: unknown noise is not counted as no noise.
Budget numerical_budget(std::vector<BudgetVariant> variants, const RunOutcome& reference,
                        const std::vector<RunOutcome>& outcomes);

}  // namespace rockcal::diagnosis
