// Ensembles: one test at one model point, run on several packings. Realisation k (0-based) of a
// request whose template has sample.seed s runs seed s + k, each as its own engine job with its own
// identity, so a larger ensemble reuses a smaller one's runs through the job cache. Sweeps and
// calibration both build their per-point statistics here.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rockcal::orch {

// The cap on "realisations" in a campaign request.
inline constexpr int kMaxRealisations = 100;

// The "realisations" of a campaign request (`value` null when absent: 1): an integer in
// [1, kMaxRealisations]. Throws std::invalid_argument saying what is wrong; the caller names the
// field.
int realisation_count(const nlohmann::json* value);

// The seeds of `count` realisations from `base_seed`: base_seed, base_seed + 1, ...
std::vector<std::uint64_t> realisation_seeds(std::uint64_t base_seed, int count);

// Why `count` (>= 1) realisations of a template cannot be run, or nullopt when they can: the seeds
// must stay within the engine's range (0 .. 2^63 - 1), and more than one realisation of a specimen
// that is the same under every seed would repeat one run and report a spread of zero.
std::optional<std::string> realisations_problem(int count, std::uint64_t base_seed,
                                                bool seed_matters);

// Mean, sample standard deviation (n - 1) and standard error sd / sqrt(n) of n values. sd and se
// need two values.
struct SampleStats {
  int n = 0;
  std::optional<double> mean;
  std::optional<double> sd;
  std::optional<double> se;
};
SampleStats sample_stats(const std::vector<double>& values);
// se / mean of the ensemble's peak load: 0 without a standard error (fewer than two values) or a
// positive mean.
double relative_se(const SampleStats& peak_load);

// One realisation as it stands: values only when its run succeeded; `error` says why a run that
// ended has none (a failed job's reason, e.g. "no peak: ...").
struct Realisation {
  std::uint64_t seed = 0;
  std::int64_t job_id = 0;  // 0 when it did not come from a service job
  std::string state;        // the job's: queued | running | succeeded | failed | cancelled
  std::optional<double> peak_load_n;
  std::optional<double> strength_pa;
  std::optional<double> youngs_modulus_pa;
  std::string error;
  // The run's own quasi-static verdict at its peak (result.json's loading_rate.quasi_static);
  // absent when the run reported none (no peak, or an engine without the measure).
  std::optional<bool> quasi_static = std::nullopt;
  std::optional<double> poisson_ratio = std::nullopt;  // a UCT's, where the run measured it
  bool cached = false;  // the job cache answered it (a run made before) without running
  // The run's whole result.json when it succeeded (what the values above do not hold: the peak
  // strain, the engine's version); null otherwise.
  nlohmann::json result = nullptr;
};

struct Ensemble {
  std::vector<Realisation> realisations;  // in seed order
  SampleStats peak_load;                  // over the realisations that succeeded
  SampleStats strength;
  SampleStats modulus;  // over those that measured one (a BTT has none)
  int failed = 0;       // realisations whose run ended without values (failed or cancelled)
};

// Sorts the realisations by seed and computes the statistics of those that succeeded.
Ensemble make_ensemble(std::vector<Realisation> realisations);

// {"mean", "sd", "se", "n"}; null where a value does not exist.
nlohmann::json to_json(const SampleStats& stats);
// {"realisations": [{"seed", "job_id", "state", "peak_load_n", "strength_pa",
//  "youngs_modulus_pa", "error"}], "peak_load": stats, "strength": stats, "modulus": stats,
//  "failed": k}
nlohmann::json to_json(const Ensemble& ensemble);

}  // namespace rockcal::orch
