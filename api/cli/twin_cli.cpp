#include "api/cli/twin_cli.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <unistd.h>

#include "api/cli/client_http.hpp"
#include "api/server/serve.hpp"
#include "api/server/views.hpp"
#include "engine/json_input.hpp"
#include "orchestrator/all_kinds.hpp"
#include "orchestrator/campaign_status.hpp"
#include "orchestrator/diagnosis/twin/twin_kind.hpp"
#include "orchestrator/job_service.hpp"
#include "orchestrator/local_executor.hpp"

namespace rockcal::api {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json read_json_file(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read " + file);
  try {
    return parse_json_input(in);
  } catch (const JsonInputError& e) {
    throw std::runtime_error(file + ": not JSON (" + e.what() + ")");
  }
}

json read_template(const std::string& file) {
  return file.empty() ? diagnosis::demo_twin_template() : read_json_file(file);
}

void write_json(const json& j, const fs::path& file) {
  std::ofstream out(file);
  out << j.dump(2) << "\n";
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

}  // namespace

int run_twin(const TwinOptions& o, const std::string& argv0) {
  using namespace rockcal::diagnosis;
  json request = {{"kind", "twin"},   {"effect", o.effect},         {"seed", o.seed},
                  {"noise", o.noise}, {"resolution", o.resolution}, {"job", read_template(o.job)}};
  if (o.value_given) request["value"] = o.value;
  if (o.truth_seed) request["truth_seed"] = *o.truth_seed;
  if (!o.next_test.empty()) {
    const json tests = read_json_file(o.next_test);
    request["next_tests"] = tests.is_array() ? tests : json::array({tests});
  }
  parse_twin_campaign(request);  // a request no twin can be made of fails before any run
  // rockcal-dem runs as an MPI singleton; Open MPI refuses root without these.
  setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 0);
  setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 0);

  // The twin's runs go through a service of its own (store and pool in <out>.runs/), the same
  // batch of jobs a server's twin, calibration or diagnosis campaign runs.
  const fs::path runs = o.out + ".runs";
  orch::ServiceConfig config;
  config.db_path = runs / "twin.db";
  config.workers = std::max(1, o.parallel);
  config.max_attempts = 1;  // the engine is deterministic: a failed run fails again
  orch::LocalExecutorConfig local;
  local.engine = o.engine.empty() ? default_engine(argv0) : o.engine;
  local.ranks = 0;
  json summary;
  std::int64_t engine_runs = 0;
  {
    fs::create_directories(runs);
    orch::JobService service(config, std::make_unique<orch::LocalExecutor>(local));
    orch::add_all_kinds(service.kinds());
    service.start();
    const std::int64_t id = service.create_campaign(request);
    // The client commands' wait loop, on this service's own campaign (progress on stderr: stdout
    // carries the dataset's table).
    watch_campaign(
        [&] {
          const db::CampaignRow row = *service.store().campaign(id);
          return std::optional<json>(
              campaign_json(row, orch::campaign_status(service.store(), row, config.workers)));
        },
        true, STDERR_FILENO);
    const std::optional<db::CampaignRow> c = service.store().campaign(id);
    engine_runs = service.store().durations(id).count;
    service.stop();
    summary = json::parse(c->summary.value_or("null"));
    if (c->driver_status == "failed") {
      throw std::runtime_error("the twin could not be made: " +
                               summary.value("error", std::string("(no reason recorded)")) +
                               "\n(runs kept in " + runs.string() + ")");
    }
  }
  const Dataset dataset = parse_dataset_json(summary.at("dataset"));
  write_dataset_file(dataset, o.out);
  const std::string truth_file = truth_file_for(o.out);
  write_json(summary.at("truth"), truth_file);
  if (!o.keep_runs) fs::remove_all(runs);

  std::printf("%-16s %-9s %-15s %-12s %14s %12s\n", "id", "test", "observable", "role", "value",
              "uncertainty");
  for (const Observation& obs : dataset.observations) {
    std::printf("%-16s %-9s %-15s %-12s %14.6g %12.4g\n", obs.id.c_str(), to_string(obs.test),
                to_string(obs.observable), to_string(obs.role), obs.value, obs.uncertainty);
  }
  const json& design = summary.at("design");
  const double ucs = design.at("base_ucs");
  const double p_low = design.at("p_low"), p_high = design.at("p_high");
  std::printf("confining pressures %g and %g Pa (%g and %g of the template's UCS %g Pa)\n", p_low,
              p_high, kLowConfinement, kHighConfinement, ucs);
  std::printf("%lld engine runs; dataset %s, truth %s (not shown)%s\n",
              static_cast<long long>(engine_runs), o.out.c_str(), truth_file.c_str(),
              o.keep_runs ? (", runs in " + runs.string()).c_str() : "");
  return 0;
}

}  // namespace rockcal::api
