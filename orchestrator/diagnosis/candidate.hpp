// One model the diagnosis compares: the base model (bond strengths only) or the base plus one
// effect whose fitted parameter walks from neutral (s = 0) to strong (s = 1).
#pragma once

#include <functional>
#include <string>

namespace rockcal::diagnosis {

struct Candidate {
  std::string effect;  // registry name; "" = the base model
  std::string param;   // the effect's params[0]
  std::string unit;
  // The parameter's value at s (effect_value_at for registry effects; a formula in tests).
  std::function<double(double s)> value_at;

  bool is_base() const { return effect.empty(); }
  int dims() const { return is_base() ? 2 : 3; }  // (ln F_r0, ln F_s0[, s]) in the unit cube
};

}  // namespace rockcal::diagnosis
