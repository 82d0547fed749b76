// The synthetic twin: a lab dataset made by the engine itself, with one effect switched on at a
// known value and bond strengths drawn from a seed, so a diagnosis can be checked against a truth
// it was not told (docs/diagnosis.md, "Twins").
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "orchestrator/diagnosis/dataset/dataset.hpp"
#include "orchestrator/diagnosis/twin/twin_design.hpp"

namespace rockcal::diagnosis {

struct TwinRequest {
  std::string effect = "none";  // an effect of engine/effects, or "none" (the null case)
  double value = 0.0;           // the effect's params[0]; ignored for "none"
  std::uint64_t seed = 1;       // the twin's packings, its lab noise and, by default, its truth
  double noise = 0.02;          // sigma of the lognormal lab noise; > 0
  // 1: a same-resolution twin (it tests identification); > 1: made by a model this many times
  // finer (engine Refinement), which tests that a resolution difference is not called an effect.
  double resolution = 1.0;
  // Draws the truth bond strengths instead of `seed`: twins of one truth seed differ in their
  // packings and lab noise only, so a matrix of them asks the model for the same design runs
  // (the local design's lattice) and spends its runs on what the twins differ in.
  std::optional<std::uint64_t> truth_seed = std::nullopt;
  // Tests measured besides the design's, as calibration observations (model units, conditions
  // stated, value 0): a diagnosis's next test, so that a twin with it shows whether the hidden
  // effect is named once that test is in the calibration set. Their noise is drawn after the
  // design's observations', so the design's values are the twin's without them.
  std::vector<Observation> next_tests = {};
};

// A next test as a diagnosis report states it (`next_test.leading.test`: id, test, observable,
// model-unit conditions; a description and other report fields are ignored), as a planned
// calibration observation. Throws orch::RequestError naming the field under `path`.
Observation parse_next_test(const nlohmann::json& test, const std::string& path);

// The twin's specimens are drawn with their own packing seed (template seed + kTwinSeedOffset +
// request seed), so its effect's random draws (heterogeneity, flaws, a random packing) are
// independent of the model's runs and of the budget's replicate seeds (template seed + 1, + 2).
inline constexpr std::uint64_t kTwinSeedOffset = 1000;

// Truth bond strengths from the seed: with the template's bond strengths (F_r, F_s) (default
// 64, 64), F_r0 = F_r exp(u1) and F_s0 = F_r0 (F_s / F_r) exp(u2), u1, u2 uniform in [-0.5, 0.5]:
// within a factor e^0.5 of the template's, with a shear/tensile ratio that varies too.
struct TruthBonds {
  double fr0_n;
  double fs0_n;
};
TruthBonds draw_truth_bonds(const JobSpec& model, std::uint64_t seed);
// The request's truth: drawn from its truth_seed if it has one, else from its seed.
TruthBonds truth_of(const JobSpec& model, const TwinRequest& request);

// Throws orch::RequestError for a request no twin can be made of, naming the field: an unknown
// "effect" or a "value" outside its range, a "noise" that is not positive, a "resolution" outside
// [1, 3], a next test whose id is no menu test's or is repeated ("next_tests[i].id").
void check_twin_request(const TwinRequest& request);

// What a twin measures: the design's observations, then the request's next tests.
std::vector<Observation> twin_observations(const TwinDesign& design, const TwinRequest& request);

// Throws orch::RequestError ("value") for an effect value that leaves the template's model as it
// is: one short of where the effect's change begins for it (first_change_of: interaction_range
// below sqrt(2) in FCC), whose twin would be a null labelled with an effect.
void check_twin_value_changes_model(const JobSpec& model, const TwinRequest& request);

// The job's "effects" block for the request: {} for "none", else {NAME: {params[0]: value}}.
// Throws orch::RequestError for an unknown effect ("effect") or a value outside its parameter's
// range ("value").
nlohmann::json twin_effects(const TwinRequest& request);

// The distinct engine jobs of the design's observations at the truth with the request's effect
// (observations one run measures, the UCT's peak, modulus and peak strain, share its job), and
// for each observation the index of its job.
struct TwinJobs {
  std::vector<nlohmann::json> jobs;
  std::vector<std::size_t> job_of;
};
TwinJobs twin_jobs(const TwinDesign& design, const TwinRequest& request, const TruthBonds& truth);

struct Twin {
  Dataset dataset;       // model units; names no effect
  nlohmann::json truth;  // what the dataset hides (FILE.truth.json)
};

// Runs the design's distinct jobs at the truth with the effect on (`run` fails on a run without a
// peak, as results_of does), reads each observation off its run, and applies the noise: value =
// noise-free x exp(noise N(0,1)), uncertainty = noise x value. The seed's stream draws u1, u2, then
// one N(0,1) per observation in design order (SplitMix64 and Box-Muller, so a seed gives the same
// twin on every platform).
Twin make_twin(const TwinDesign& design, const TwinRequest& request, const RunJobs& run);

// FILE.json or FILE.csv -> FILE.truth.json (any other name: NAME.truth.json).
std::string truth_file_for(const std::string& dataset_file);

}  // namespace rockcal::diagnosis
