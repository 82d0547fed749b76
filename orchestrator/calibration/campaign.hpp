// A campaign of kind "calibration": what to match, where to search, how long, how.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "orchestrator/calibration/specimen.hpp"
#include "orchestrator/calibration/targets.hpp"
#include "orchestrator/request_error.hpp"

namespace rockcal::calibration {

// auto: ratio-then-scale when the measured homogeneity holds, else the 2-D search. bayes: the
// inference core (emulators of both loads over the log box, batches of runs where they most shrink
// the posterior, a credible region as the answer; bayes/search.hpp).
enum class Strategy { automatic, ratio_scale, direct_2d, bayes };

// What the "bayes" strategy needs beyond the targets ("inference": {...}).
struct InferenceSettings {
  // Relative standard deviation of each lab mean (a target known to 5% is ln-normal with sd
  // about 0.05); `*_stated` say whether the request gave each or the default stands.
  double lab_uct = 0.05;
  double lab_btt = 0.05;
  bool lab_uct_stated = false, lab_btt_stated = false;  // which of the two the request gave
  bool lab_stated() const { return lab_uct_stated || lab_btt_stated; }
  double discrepancy = 0.0;   // relative sd of the model's stated discrepancy on both loads
  double level = 0.9;         // of the credible region
  double unique_width = 1.5;  // pinned: each strength's interval spans at most this factor
  int batch = 0;              // runs per round; 0: the pool's workers (at least 2)
};

// A further lab test the "bayes" strategy matches besides the UCT and the BTT: a test from the
// engine's menu at a patch of the job template (what a report's next test names), e.g. a squat UCT
// or a triaxial at a confinement. Every run then runs it too, and it has its own emulator.
struct FurtherTarget {
  std::string name;  // as the report shows it
  TestKind test = TestKind::uct;
  nlohmann::json patch;  // merged into the job template (model units)
  double value = 0.0;    // the peak load as given (N, in the targets' units)
  double model_n = 0.0;  // the same in model units
  double sd = 0.05;      // relative sd of the lab value
};

struct Range {
  double lo;
  double hi;
};

// A [lower, upper] pair of bond strengths for a search in log space: finite, 0 < lower < upper.
// Errors name `field` (e.g. "bounds.fr0[1]").
Range parse_log_range(const nlohmann::json& value, const std::string& field);

struct CalibrationCampaign {
  std::string name;
  nlohmann::json job_template;    // the "job" block: no "test", no "bond" (the search sets both)
  Specimen model_specimen;        // the template's sample, for strengths in model units
  std::uint64_t sample_seed = 1;  // the template's packing seed, used by the search
  bool seed_matters = true;       // other seeds give other specimens (engine's seed_matters)
  int realisations = 1;  // packings per evaluation: seeds sample_seed, sample_seed + 1, ...
  // "realisations": "auto" (ensemble_size.hpp): the size comes from a pilot's scatter, at most
  // this.
  bool auto_realisations = false;
  int max_realisations = 8;
  Targets targets;
  Range fr0_n{1, 1000};
  Range fs0_n{1, 1000};
  int max_evaluations = 40;  // points evaluated by the search (each = realisations x UCT + BTT)
  double tolerance = 0.02;   // relative, on each peak load
  double weight_uct = 1.0;
  double weight_btt = 1.0;
  std::string algorithm = "bobyqa";
  Strategy strategy = Strategy::automatic;
  InferenceSettings inference;
  int initial_points = 4;                    // Latin hypercube points of the space-filling start
  std::uint64_t random_seed = 1;             // Latin hypercube and nlopt::srand
  double homogeneity_tolerance = 0.1;        // accepted |exponent_uct - exponent_btt|
  std::vector<std::uint64_t> scatter_seeds;  // extra packing seeds for the best point
  int consistency_evaluations = 24;          // the consistent-set trace after the search (0: none)
  bool suggest = true;  // measure the observable that would pin a non-unique set
  // Multi-fidelity (fidelity.hpp): a merge patch of the job template that makes the fine specimen
  // (null: the search's specimen is the answer), and the fine evaluations allowed.
  nlohmann::json fine_patch = nullptr;
  int fine_corrections = 3;
  // With "strategy": "bayes": the fine runs (UCT + BTT, one packing each) after the coarse search,
  // pooled with the coarse runs in one two-level emulator (inference/emulator/two_level.hpp).
  int fine_runs = 12;
  std::vector<FurtherTarget> further;  // "further_targets", only with "strategy": "bayes"
  // F on the fine specimen = F of the search x this: (R_fine / R_coarse)^2 when the fine specimen
  // has smaller grains at the same stress scale (bond forces scale with the bond's area).
  double fine_strength_scale = 1.0;
  // "reach": {"interaction_range": [...]}: the interaction ranges the calibration may take, tried
  // in order while the target UCT/BTT load ratio lies outside what a range's runs reached
  // (reach.hpp). Empty: the template's own bond network.
  std::vector<double> interaction_ranges;
};

// The pilot ensemble that measures the scatter for "realisations": "auto".
inline constexpr int kPilotRealisations = 3;

// Parses and validates the whole campaign (the job template through the engine's validation for
// both tests). Throws orch::RequestError naming the first offending field.
CalibrationCampaign parse_calibration_campaign(const nlohmann::json& campaign);

const char* to_string(Strategy strategy);

}  // namespace rockcal::calibration
