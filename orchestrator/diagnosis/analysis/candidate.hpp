// One model the diagnosis compares: the base model (bond strengths only) or the base plus one
// effect whose fitted parameter walks from neutral (s = 0) to strong (s = 1).
#pragma once

#include <functional>
#include <string>

#include "engine/effects/effect.hpp"

namespace rockcal::diagnosis {

// Where a discontinuous effect's exploration starts: a quarter of its walk (packing: radius ratio
// 1.25), close enough to neutral to reach mild cases and far enough for the specimen to be random.
inline constexpr double kDiscontinuousFloor = 0.25;

struct Candidate {
  std::string effect;  // registry name; "" = the base model
  std::string param;   // the effect's params[0]
  std::string unit;
  // The parameter's value at s (effect_value_at for registry effects; a formula in tests).
  std::function<double(double s)> value_at;
  // The values that give the same model as a fitted one (registry effects:
  // effect_same_model_span; interaction_range in FCC: its shell of neighbours). Empty, or from ==
  // to: the value alone.
  std::function<ValueSpan(double value)> same_model{};
  // The walk fraction the candidate's unit coordinate u = 0 stands for: s = floor + (1 - floor) u.
  // 0 for an effect continuous at neutral (u = 0 is the base model, whose grid it shares); above 0
  // for one that jumps there (packing), whose own grid then starts at the floor.
  double s_floor = 0.0;

  bool is_base() const { return effect.empty(); }
  bool shares_base_grid() const { return s_floor <= 0.0; }
  double s_at(double u) const { return s_floor + (1.0 - s_floor) * u; }
  int dims() const { return is_base() ? 2 : 3; }  // (ln F_r0, ln F_s0[, s]) in the unit cube
};

}  // namespace rockcal::diagnosis
