// The diagnosis's only view of the engine: "run the conditions of every target at this model point
// (bond strengths, optionally one effect at fraction s of its range), with these numerics"; the
// targets are the dataset's, or others (the next test's menu, next_test.hpp).
// The service implements it over the one job runner (the pipeline's RunnerEvaluator, on the
// pool); the unit tests with formulas in which each hidden effect leaves its own signature.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "orchestrator/diagnosis/analysis/observations.hpp"

namespace rockcal::diagnosis {

// How the engine discretises and drives the test: the budget varies these, nothing else does.
struct Numerics {
  std::uint64_t seed = 1;     // packing seed
  double speed_factor = 1.0;  // platen speed multiplier (the budget halves it)
  double resolution = 1.0;    // particles per length multiplier (the budget refines by 1.25)
  bool operator==(const Numerics&) const = default;
};

// A model: bond strengths (model units, N) and at most one effect, at fraction s in [0, 1] of the
// way from neutral to strong (effect_value_at). s = 0 or no effect is the base model.
struct ModelPoint {
  double fr0_n = 0.0;
  double fs0_n = 0.0;
  std::string effect;  // "" = base model
  double s = 0.0;
  bool operator==(const ModelPoint&) const = default;
};

struct RunRequest {
  ModelPoint point;
  Numerics numerics;
};

// One value per target, in the evaluator's target order (model units); nullopt where the run that
// measures it failed (a run that ended without a peak is a failed run). `error` is the first
// failure.
struct RunOutcome {
  std::vector<std::optional<double>> values;
  std::string error;
};

// Thrown by an evaluator when the campaign is cancelled or the server stops.
struct DiagnosisCancelled : std::runtime_error {
  DiagnosisCancelled() : std::runtime_error("diagnosis cancelled") {}
};

class Evaluator {
 public:
  virtual ~Evaluator() = default;
  // Runs every request (all at once, in parallel where possible) and blocks until all have ended.
  // Asking again for a request already run must give the same outcome (the job cache does), which
  // is what makes a restarted diagnosis replay instead of recompute. May throw DiagnosisCancelled.
  virtual std::vector<RunOutcome> run_batch(std::span<const RunRequest> requests) = 0;
  // The same on the conditions of `targets` instead of the evaluator's own (tests the dataset does
  // not have): each outcome has one value per given target, in their order.
  virtual std::vector<RunOutcome> run_on(std::span<const RunRequest> requests,
                                         const std::vector<Target>& targets) = 0;
};

// An effect is "on" in a job only above this s: s = 0 must give the base model's very job, so the
// base grid doubles as every candidate's s = 0 slice and the cache recognises it.
inline constexpr double kEffectOffBelow = 1e-9;

inline bool effect_on(const ModelPoint& p) {
  return !p.effect.empty() && p.s > kEffectOffBelow;
}

}  // namespace rockcal::diagnosis
