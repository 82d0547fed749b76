// Data that disagree with themselves: two observations of one observable under nearly the same
// conditions whose values differ by more than their stated uncertainties allow (two labs' UCS of
// one rock, say).
//
// Why: no model meets both values of such a pair, so a diagnosis that charged their difference to
// the model would call the data's own disagreement a gap. The pair is named, and a residual of
// either is charged only beyond the span of the values the data give there (charged_residuals,
// gap.hpp): a model anywhere between the two values is not charged, one outside them is charged
// its distance to the nearer value.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "orchestrator/diagnosis/analysis/observations.hpp"

namespace rockcal::diagnosis {

// "Nearly the same conditions": the same test and observable, and each of these within its
// tolerance, relative to the larger of the two values (resolved conditions, observations.hpp):
// - the specimen's sizes (diameter; height of a cylinder, thickness of a disc): 1% for a peak
//   load, which scales with the loaded area (1% in size is at most about 2% in load); 5% for a
//   strength, modulus or peak strain, which move with size only through the size effect (UCS
//   as d^-0.18, Hoek & Brown 1980: under 1% over 5%);
// - the confining pressure and the platen speed: 1% (both are effects a candidate may model, so
//   a larger difference is a condition the model should tell apart, not a replicate).
inline constexpr double kSameSizeForLoads = 0.01;
inline constexpr double kSameSizeForIntensive = 0.05;
inline constexpr double kSameLoading = 0.01;
bool same_conditions(const Target& a, const Target& b);

// Beyond this many combined standard deviations a pair disagrees: honest values cross it 0.3%
// of the time.
inline constexpr double kDisagreementSd = 3.0;

struct Inconsistency {
  std::size_t first = 0, second = 0;  // target indices, first < second
  double ln_difference = 0.0;         // ln(second / first)
  double sigmas = 0.0;  // |ln difference| over the pair's combined relative sd (in quadrature)
};

// Every pair under nearly the same conditions more than kDisagreementSd combined sd apart.
std::vector<Inconsistency> find_inconsistencies(const std::vector<Target>& targets);

// Per target, the ln(value) span [lo, hi] (lo <= 0 <= hi, relative to its own value) of the
// values it disagrees with; [0, 0] for a target in no inconsistent pair.
struct DataSpan {
  double lo = 0.0, hi = 0.0;
};
std::vector<DataSpan> data_spans(const std::vector<Target>& targets);

// "uct-1 and uct-2 (uct peak_load, nearly the same conditions) differ by +20% in value, 6.4
// times their combined uncertainty": one clause per pair, "; " between.
std::string inconsistency_text(const std::vector<Inconsistency>& pairs,
                               const std::vector<Target>& targets);

}  // namespace rockcal::diagnosis
