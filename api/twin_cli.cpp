#include "api/twin_cli.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "api/serve.hpp"
#include "engine/json_input.hpp"
#include "orchestrator/diagnosis/twin/engine_runs.hpp"
#include "orchestrator/diagnosis/twin/twin.hpp"
#include "orchestrator/diagnosis/twin/twin_design.hpp"

namespace rockcal::api {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json read_template(const std::string& file) {
  if (file.empty()) return diagnosis::demo_twin_template();
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read " + file);
  try {
    return parse_json_input(in);
  } catch (const JsonInputError& e) {
    throw std::runtime_error(file + ": not JSON (" + e.what() + ")");
  }
}

void write_json(const json& j, const fs::path& file) {
  std::ofstream out(file);
  out << j.dump(2) << "\n";
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

}  // namespace

int run_twin(const TwinOptions& o, const std::string& argv0) {
  using namespace rockcal::diagnosis;
  if (o.effect != "none" && !o.value_given) {
    throw std::runtime_error("--value is required with --effect " + o.effect);
  }
  const TwinRequest request{o.effect, o.value, o.seed, o.noise, o.resolution};
  check_twin_request(request);  // a request no twin can be made of fails before any run
  // rockcal-dem runs as an MPI singleton; Open MPI refuses root without these.
  setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 0);
  setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 0);

  const fs::path runs = o.out + ".runs";
  EngineRunner runner({o.engine.empty() ? default_engine(argv0) : o.engine, o.parallel, runs});
  const RunJobs run = [&](const std::vector<json>& jobs) { return runner.run(jobs); };
  const TwinDesign design = make_twin_design(read_template(o.job), run);
  const Twin twin = make_twin(design, request, run);

  write_dataset_file(twin.dataset, o.out);
  const std::string truth_file = truth_file_for(o.out);
  write_json(twin.truth, truth_file);
  if (!o.keep_runs) fs::remove_all(runs);

  std::printf("%-12s %-9s %-15s %-12s %14s %12s\n", "id", "test", "observable", "role", "value",
              "uncertainty");
  for (const Observation& obs : twin.dataset.observations) {
    std::printf("%-12s %-9s %-15s %-12s %14.6g %12.4g\n", obs.id.c_str(), to_string(obs.test),
                to_string(obs.observable), to_string(obs.role), obs.value, obs.uncertainty);
  }
  std::printf("confining pressures %g and %g Pa (%g and %g of the template's UCS %g Pa)\n",
              design.p_low_pa, design.p_high_pa, kLowConfinement, kHighConfinement,
              design.base_ucs_pa);
  std::printf("%d engine runs; dataset %s, truth %s (not shown)%s\n", runner.runs_started(),
              o.out.c_str(), truth_file.c_str(),
              o.keep_runs ? (", runs in " + runs.string()).c_str() : "");
  return 0;
}

}  // namespace rockcal::api
