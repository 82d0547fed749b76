#include "orchestrator/diagnosis/twin/twin_kind.hpp"

#include <limits>
#include <stdexcept>

#include "orchestrator/json_fields.hpp"
#include "orchestrator/pool_runner.hpp"
#include "orchestrator/progress_model.hpp"
#include "orchestrator/request_error.hpp"
#include "orchestrator/request_fields.hpp"

namespace rockcal::diagnosis {

using nlohmann::json;

TwinCampaign parse_twin_campaign(const json& request) {
  orch::JsonFields f(request, "");
  f.get("kind");
  TwinCampaign c;
  c.name = orch::campaign_name(request, "twin");
  f.get("name");
  c.twin.effect = f.string("effect").value_or("");
  if (c.twin.effect.empty())
    throw orch::RequestError("effect", "is required (an effect or \"none\")");
  const auto value = f.number("value");
  if (!value && c.twin.effect != "none") {
    throw orch::RequestError("value", "is required with effect " + c.twin.effect);
  }
  c.twin.value = value.value_or(0.0);
  c.twin.seed =
      std::uint64_t(f.integer("seed", 0, std::numeric_limits<std::int64_t>::max()).value_or(1));
  if (const auto t = f.integer("truth_seed", 0, std::numeric_limits<std::int64_t>::max()))
    c.twin.truth_seed = std::uint64_t(*t);
  c.twin.noise = f.number("noise").value_or(c.twin.noise);
  c.twin.resolution = f.number("resolution").value_or(c.twin.resolution);
  if (const json* tests = f.get("next_tests")) {
    if (!tests->is_array()) {
      throw orch::RequestError("next_tests", "must be a list of a report's next tests");
    }
    for (std::size_t i = 0; i < tests->size(); ++i) {
      c.twin.next_tests.push_back(
          parse_next_test((*tests)[i], "next_tests[" + std::to_string(i) + "]"));
    }
  }
  const json* job = f.get("job");
  c.job_template = job ? *job : demo_twin_template();
  f.reject_unknown();
  check_twin_request(c.twin);
  check_twin_value_changes_model(check_twin_template(c.job_template), c.twin);
  return c;
}

RunJobs results_of(orch::JobRunner& runner) {
  return [&runner](const std::vector<json>& jobs) {
    const std::optional<std::vector<orch::Realisation>> runs = runner.run(jobs);
    if (!runs) throw TwinCancelled();
    std::vector<json> results;
    for (const orch::Realisation& run : *runs) {
      if (!run.result.is_object()) {
        throw std::runtime_error("twin job " + std::to_string(run.job_id) + " " + run.state + ": " +
                                 run.error);
      }
      results.push_back(run.result);
    }
    return results;
  };
}

std::vector<orch::BudgetPart> planned_twin_job_parts(const TwinCampaign& c) {
  // Laid out without running: every run answers a placeholder base UCS, on which no count
  // depends (the confining pressures are two fractions of it, distinct for any UCS).
  const RunJobs lay_out = [](const std::vector<json>& jobs) {
    return std::vector<json>(jobs.size(), json{{"strength", 1.0}});
  };
  const TwinDesign design = make_twin_design(c.job_template, lay_out);
  const TruthBonds truth = truth_of(design.model, c.twin);
  return {{"design", 1}, {"observations", int(twin_jobs(design, c.twin, truth).jobs.size())}};
}

orch::CampaignKind twin_kind() {
  orch::CampaignKind kind;
  kind.name = "twin";
  kind.plan = [](const json& request, const orch::Limits&) {
    return orch::CampaignPlan{parse_twin_campaign(request).name, {}};
  };
  kind.driver = [](orch::DriverContext& ctx) {
    const TwinCampaign c = parse_twin_campaign(ctx.request);
    // Before each batch the summary carries the progress model: jobs done (counted by the service
    // as it is read, orchestrator/campaign_status.hpp) of the ones the twin plans.
    const std::vector<orch::BudgetPart> parts = planned_twin_job_parts(c);
    auto model = [&](bool finished) {
      return orch::progress_model_json("jobs",
                                       int(ctx.service.store().counts(ctx.campaign_id).ended()),
                                       parts, 0, std::nullopt, finished);
    };
    orch::PoolRunner runner(ctx.service, ctx.campaign_id, ctx.stop);
    const RunJobs pool = results_of(runner);
    const RunJobs run = [&](const std::vector<json>& jobs) {
      ctx.service.store().set_driver_status(ctx.campaign_id, "running",
                                            json{{"progress", model(false)}}.dump());
      return pool(jobs);
    };
    const TwinDesign design = make_twin_design(c.job_template, run);
    const Twin twin = make_twin(design, c.twin, run);
    return json{{"kind", "twin"},
                {"progress", model(true)},
                {"name", c.name},
                {"dataset", to_json(twin.dataset)},
                {"truth", twin.truth},
                {"design",
                 {{"base_ucs", design.base_ucs_pa},
                  {"p_low", design.p_low_pa},
                  {"p_high", design.p_high_pa},
                  {"units", "model"}}}};
  };
  return kind;
}

}  // namespace rockcal::diagnosis
