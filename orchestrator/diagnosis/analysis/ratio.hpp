// The attainable UCT/BTT ratio: the seed paper's gap (model 10, lab 6) in one number. Over the
// base grid, which spans the bounds, the ratio of the first calibration UCT and BTT peak loads (or
// strengths, when the dataset has no peak loads of both) against the lab's.
#pragma once

#include <optional>
#include <vector>

#include "orchestrator/diagnosis/analysis/evaluator.hpp"
#include "orchestrator/diagnosis/analysis/observations.hpp"
#include "orchestrator/ratio_range.hpp"

namespace rockcal::diagnosis {

// UCT/BTT peak ratio between two calibration targets, over the base grid runs.
struct LabRatio {
  std::size_t uct = 0, btt = 0;  // target indices
  orch::RatioRange range;        // target: the lab's ratio of the two
};

std::optional<LabRatio> ratio_range(const std::vector<Target>& targets,
                                    const std::vector<RunOutcome>& base_grid);

}  // namespace rockcal::diagnosis
