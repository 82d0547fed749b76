// The calibration's only view of the engine: "run the UCT and the BTT of these bond strengths".
// The orchestrator implements it on its worker pool; the tests implement it with formulas.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/spec.hpp"
#include "orchestrator/ensemble.hpp"

namespace rockcal::calibration {

// Bond strengths in model units (N).
struct BondPoint {
  double fr0_n;  // tensile
  double fs0_n;  // shear
  bool operator==(const BondPoint&) const = default;
};

// Peak loads of the two tests of one point, model units (N).
struct PeakLoads {
  double uct_n;
  double btt_n;
};

// One evaluation: a point run on `realisations` samples packed with seeds sample_seed,
// sample_seed + 1, ... (orch::realisation_seeds; the search uses the job template's seed, the final
// uncertainty scatter re-runs the best point with other seeds).
struct EvaluationRequest {
  BondPoint point;
  std::uint64_t sample_seed;
  int realisations = 1;
  std::string phase{};  // what the search runs it for ("start", "design", "check"); else empty
};

// The loads of an evaluation are the ensemble means of each test's peak load over the realisations
// that reached a peak; `uct` and `btt` hold the realisations and their statistics (the standard
// error of each mean is uct->peak_load.se). A failed evaluation (no realisation of a test reached a
// peak: jobs failed after their retries, crashed, timed out, ended without a peak) carries no loads
// and a message; the driver turns it into a penalty, never a NaN for NLopt.
struct EvaluationOutcome {
  std::optional<PeakLoads> loads;
  std::string error;
  std::optional<orch::Ensemble> uct;  // absent from evaluators that do not report realisations
  std::optional<orch::Ensemble> btt;
  bool ok() const { return loads.has_value(); }
};

// The outcome of an evaluation from its two ensembles: loads when each test has a peak load from
// at least one realisation, else the first failed realisation's error.
EvaluationOutcome outcome_of(orch::Ensemble uct, orch::Ensemble btt);

// Thrown by an evaluator (or the driver) when the campaign is cancelled; the driver stops the
// optimiser and reports what it has.
struct EvaluationCancelled : std::runtime_error {
  EvaluationCancelled() : std::runtime_error("calibration cancelled") {}
};

// A further test of a point beyond the two the targets use (a triaxial at a confinement, a disc of
// another size): what the report's suggestion measures across the consistent set. `patch` is
// merged into the job template (a JSON merge patch) before the test, strengths and seed are set.
struct ProbeRequest {
  BondPoint point;
  std::uint64_t sample_seed;
  int realisations = 1;
  TestKind test = TestKind::uct;
  nlohmann::json patch = nlohmann::json::object();
};

class Evaluator {
 public:
  virtual ~Evaluator() = default;
  // Runs the UCT and the BTT of every request, blocking until all have finished, and returns one
  // outcome per request in request order. Implementations should run the requests (and the two
  // tests of each) concurrently: the space-filling start and the seed scatter come as one batch.
  // Asking again for a request already run must give the same outcome (the job cache does this),
  // which is what lets a restarted campaign replay its history. May throw EvaluationCancelled.
  virtual std::vector<EvaluationOutcome> evaluate_batch(
      std::span<const EvaluationRequest> requests) = 0;
  // Runs each probe's realisations concurrently: one ensemble per probe, in order. An evaluator
  // that runs only the two target tests returns none, and the report suggests from what the
  // search itself measured.
  virtual std::vector<orch::Ensemble> probe_batch(std::span<const ProbeRequest> probes) {
    (void)probes;
    return {};
  }
  // Merges `patch` into the job template of every later run, evaluation or probe (the stiffness
  // stage's bond stiffnesses, stiffness.hpp). An evaluator that runs formulas of the strengths
  // alone has no template and nothing to change.
  virtual void patch_template(const nlohmann::json& patch) { (void)patch; }
};

// The full job (test, bond strengths, seed filled in) that evaluates one test of a request on the
// sample packed with `seed` (one of the request's realisation seeds): what the orchestrator submits
// to its pool. `job_template` is the campaign's "job" block.
nlohmann::json job_for(const nlohmann::json& job_template, const EvaluationRequest& request,
                       TestKind test, std::uint64_t seed);
// The same for a probe: the template with the probe's patch merged in.
nlohmann::json job_for(const nlohmann::json& job_template, const ProbeRequest& probe,
                       std::uint64_t seed);

}  // namespace rockcal::calibration
