// Data that disagree with themselves: two observations of the same observable under the same
// conditions (the same test and specimen, confinement and loading rate within 1%) whose values
// differ by more than their stated uncertainties allow (two labs' UCS of one rock, say).
//
// Why: a model cannot meet both values of such a pair, so a diagnosis that charged their difference
// to the model would name a gap the data made. The pair is reported, named, as the data's own.
#pragma once

#include <string>
#include <vector>

#include "orchestrator/diagnosis/dataset/dataset.hpp"

namespace rockcal::diagnosis {

struct Inconsistency {
  std::string first, second;   // the observations' ids, in dataset order
  double ln_difference = 0.0;  // ln(second / first)
  double sigmas = 0.0;         // |ln difference| over the pair's combined relative sd
};

// Every pair whose difference exceeds `z` combined standard deviations (relative uncertainties
// in ln, added in quadrature). Default z = 3: a pair of honest values crosses it 0.3% of the time.
std::vector<Inconsistency> find_inconsistencies(const Dataset& d, double z = 3.0);

// "uct-1 and uct-2 (the same UCT) differ by +35% (4.1 sd)": one clause per pair, "; " between.
std::string inconsistency_text(const std::vector<Inconsistency>& pairs);

}  // namespace rockcal::diagnosis
