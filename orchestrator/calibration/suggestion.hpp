// When the consistent set is not one point, the lab observable that would pin it: the one whose
// value differs most between the set's two ends (its smallest and its largest F_s0/F_r0). Two
// loads fixed, the bonds' stiffness fixed, the UCT's modulus and peak strain barely move along the
// set; what tells its members apart is a test that weighs the two strengths differently. So the
// candidates are the UCT modulus (every evaluation measured it already), a triaxial peak at a
// confinement of kTriaxialConfinement x the target UCS, and the BTT peak of a disc kBttSizeFactor
// times the diameter; the last two are run at the two ends (the campaign's realisations each).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "orchestrator/calibration/consistent_set.hpp"

namespace rockcal::calibration {

inline constexpr double kTriaxialConfinement = 0.1;
inline constexpr double kBttSizeFactor = 1.5;

struct ObservableValue {
  BondPoint point;
  double value = 0.0;        // mean over the realisations
  std::optional<double> se;  // its standard error, with two realisations or more
};

struct Suggestion {
  std::string observable;               // what to measure in the lab, with its conditions
  std::string unit;                     // of the values (model units)
  std::vector<ObservableValue> values;  // at the set's ends, smallest F_s0/F_r0 first
  double spread = 0.0;                  // |ln(last / first)|
  std::string why;
  // Every candidate measured, with its spread: the suggestion is the largest. With
  // `expected_shrinkage` (the bayes strategy's next test) the value is instead the expected
  // shortening of the credible region's long axis, a fraction.
  std::vector<std::pair<std::string, double>> candidates;
  bool expected_shrinkage = false;
};

// Nothing when the set is unique or has fewer than two distinct points. Throws
// EvaluationCancelled like the evaluator.
std::optional<Suggestion> suggest_observable(const ConsistentSet& set,
                                             const CalibrationCampaign& campaign,
                                             Evaluator& evaluator);

}  // namespace rockcal::calibration
