// How firm the verdict is against the noise it was judged under. Each replicate redraws every lab
// value as ln y + N(0, sigma^2 + budget^2) (lab scatter and numerical noise), re-fits the base and
// every fitted effect on its surfaces, and replays the verdict rule on their evidence
// (evidence.hpp); the confidence is the share of replicates that reach the nominal verdict. A
// confirmed candidate's prediction in a replicate is its real run shifted by the surface's change
// between the nominal and the replicate's fit, so surface error at the fitted point does not
// enter. `budget` weights the re-fits (as it weighted the nominal ones); `judged`, the budget at
// the confirmed base fit, is the noise drawn and the variance of the replayed evidence.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "orchestrator/diagnosis/analysis/observations.hpp"
#include "orchestrator/diagnosis/analysis/verdict.hpp"

namespace rockcal::diagnosis {

struct BootstrapResult {
  int replicates = 0;
  std::map<std::string, int> winners;  // effect name ("" = no effect needed) -> replicates
};

// Deterministic: draws come from mt19937_64(seed) through Box-Muller (std's normal distribution
// differs between standard libraries).
BootstrapResult bootstrap_verdicts(const DecisionRule& rule,
                                   const std::vector<CandidateResult>& candidates,
                                   const std::vector<Target>& targets,
                                   const std::vector<double>& budget,
                                   const std::vector<double>& judged, int replicates,
                                   std::uint64_t seed);

// The objective weights: 1 / (sigma^2 + budget^2) on calibration targets with a surface, 0
// elsewhere (a floor of 0.1% keeps an exact lab value from taking all the weight).
Objective calibration_objective(const std::vector<Target>& targets,
                                const std::vector<double>& budget, const SurfaceSet& surfaces,
                                std::vector<double> ln_lab);

}  // namespace rockcal::diagnosis
