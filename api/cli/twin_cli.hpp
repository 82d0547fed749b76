// `rockcal twin`: writes a synthetic lab dataset made by the engine with a hidden effect, and the
// truth beside it (docs/diagnosis.md, "Twins").
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace rockcal::api {

struct TwinOptions {
  std::string effect;  // an engine effect, or "none"
  double value = 0.0;  // its params[0]; required unless the effect is "none"
  bool value_given = false;
  std::uint64_t seed = 1;
  std::optional<std::uint64_t> truth_seed;  // draws the truth instead of seed
  std::string job;  // template file; default: the demo sample (twin_cli.cpp)
  double noise = 0.02;
  double resolution = 1.0;        // > 1: a finer-model twin
  std::string engine;             // default: default_engine()
  std::string out = "twin.json";  // .json or .csv; the truth goes to <out minus .json>.truth.json
  int parallel = 2;               // engine runs at once
  bool keep_runs = false;         // keep <out>.runs/ (job dirs and logs) after success
  std::string next_test;          // JSON file: a report's next test, or a list of them
};

int run_twin(const TwinOptions& options, const std::string& argv0);

}  // namespace rockcal::api
