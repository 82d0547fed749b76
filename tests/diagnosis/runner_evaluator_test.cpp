// The diagnosis's evaluator over the service's pool (RunnerEvaluator on orch::PoolRunner) with the
// fake engine: a run that ended without a peak is a failed job, and the diagnosis sees a failed run
// with that reason, never its largest load (nor the modulus of that run).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "orchestrator/all_kinds.hpp"
#include "orchestrator/diagnosis/pipeline/runner_evaluator.hpp"
#include "orchestrator/local_executor.hpp"
#include "orchestrator/pool_runner.hpp"

namespace rockcal::diagnosis {
namespace {

using nlohmann::json;

Target uct_target(const char* id, Observable observable) {
  Target t;
  t.id = id;
  t.observable = observable;
  t.conditions = {TestKind::uct, 6, 12, 3, 0, 0.05};
  t.value = 1;
  t.sigma = 0.02;
  return t;
}

TEST(DiagnosisPool, ARunWithoutAPeakIsAFailedRunWithItsReason) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("rockcal-diag-pool-" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  orch::ServiceConfig cfg;
  cfg.db_path = dir / "svc.db";
  cfg.workers = 2;
  orch::LocalExecutorConfig exec;
  exec.engine = FAKE_ENGINE;
  exec.ranks = 0;
  {
    orch::JobService service(cfg, std::make_unique<orch::LocalExecutor>(exec));
    orch::add_all_kinds(service.kinds());
    service.start();
    const json job_template = {{"sample", {{"diameter", 6}, {"height", 12}, {"radius", 1}}},
                               {"material", {{"kr", 8000}, {"nu", 0.2}, {"density", 1}}},
                               {"loading", {{"platen_velocity", 0.05}}}};
    // A campaign for the evaluator's jobs (its own one job runs too).
    const std::int64_t campaign = service.create_campaign(
        {{"kind", "sweep"}, {"tests", {"uct"}}, {"job", job_template}, {"points", {{1, 1}}}});
    orch::PoolRunner pool(service, campaign, {});
    RunnerEvaluator evaluator(pool, job_template,
                              {uct_target("uct-peak", Observable::peak_load),
                               uct_target("uct-modulus", Observable::youngs_modulus)});
    // fr0 61: the fake engine's run reaches no peak; fr0 50: peak 50, modulus 1000.
    const std::vector<RunRequest> requests = {{{61, 60, "", 0}, {1, 1, 1}},
                                              {{50, 60, "", 0}, {1, 1, 1}}};
    const std::vector<RunOutcome> out = evaluator.run_batch(requests);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0].values, (std::vector<std::optional<double>>{std::nullopt, std::nullopt}));
    EXPECT_EQ(out[0].error,
              "no peak: the load fell on a loose particle with no bond broken (fake)");
    EXPECT_EQ(out[1].values, (std::vector<std::optional<double>>{50.0, 1000.0}));
    EXPECT_EQ(out[1].error, "");
    service.stop();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rockcal::diagnosis
