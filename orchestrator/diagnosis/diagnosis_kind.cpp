#include "orchestrator/diagnosis/diagnosis_kind.hpp"

#include "orchestrator/diagnosis/pipeline/driver.hpp"
#include "orchestrator/diagnosis/pipeline/grid.hpp"
#include "orchestrator/diagnosis/pipeline/jobs.hpp"
#include "orchestrator/diagnosis/pipeline/next_test_runs.hpp"
#include "orchestrator/diagnosis/pipeline/runner_evaluator.hpp"
#include "orchestrator/diagnosis/report/report.hpp"
#include "orchestrator/job_service.hpp"
#include "orchestrator/pool_runner.hpp"
#include "orchestrator/request_error.hpp"

namespace rockcal::diagnosis {

std::vector<orch::BudgetPart> planned_job_parts(const DiagnosisCampaign& c) {
  const int runs = int(plan_runs(c.targets).runs.size());
  const int seeds = int(c.budget.seeds.size());
  // Measured at the base model's first fit, with the screen's runs, and, if it moved, again at its
  // confirmed fit.
  const int budget = 2 * int(budget_offsets(c.budget.points).size()) *
                         int(budget_runs_per_point(c.budget, c.dataset.origin)) +
                     screen_model_points(c);
  // Effects are designed and confirmed only when held-out observations can judge them; each
  // confirmed effect also runs the base model at its strengths (its mark at its fitted value).
  const bool judged = judges_effects(c);
  const int confirm = (1 + c.refine + seeds) + (judged ? c.confirm * (2 + c.refine + seeds) : 0);
  const int grid = judged ? grid_points(c) : base_grid_points(c);
  std::vector<orch::BudgetPart> parts{
      {"grid", grid * runs}, {"budget", budget * runs}, {"confirm", confirm * runs}};
  // The next test's batch runs on the dataset's and the menu's conditions.
  const int next_test = c.next_test ? next_test_model_points(c) : 0;
  if (next_test > 0) {
    const std::vector<Target> all = with_menu(c.targets, test_menu(c.targets));
    parts.push_back({"next_test", next_test * int(plan_runs(all).runs.size())});
  }
  return parts;
}

std::size_t planned_jobs(const DiagnosisCampaign& c) {
  std::size_t jobs = 0;
  for (const orch::BudgetPart& p : planned_job_parts(c)) jobs += std::size_t(p.budget);
  return jobs;
}

orch::CampaignKind diagnosis_kind() {
  orch::CampaignKind kind;
  kind.name = "diagnosis";
  kind.plan = [](const nlohmann::json& request, const orch::Limits& limits) {
    const DiagnosisCampaign c = parse_diagnosis_campaign(request);
    if (planned_jobs(c) > limits.max_jobs_per_campaign) {
      throw orch::RequestError(
          "grid", "the diagnosis may need " + std::to_string(planned_jobs(c)) +
                      " jobs, above the server's cap of " +
                      std::to_string(limits.max_jobs_per_campaign) +
                      " per campaign: a smaller grid, grid.design \"local\", fewer effects or "
                      "\"next_test\": false");
    }
    return orch::CampaignPlan{c.name, {}};
  };
  // Runs in the service's driver thread; a restart after a crash runs it again from the stored
  // request, and the job cache replays the finished runs.
  kind.driver = [](orch::DriverContext& ctx) {
    const DiagnosisCampaign c = parse_diagnosis_campaign(ctx.request);
    orch::PoolRunner pool(ctx.service, ctx.campaign_id, ctx.stop);
    RunnerEvaluator evaluator(pool, c.job_template, c.targets);
    DiagnosisOptions options;
    options.stop = ctx.stop;
    // While it runs, the summary says which phase it is in and carries the progress model: jobs
    // done of the planned parts (the service counts the jobs done as it is read,
    // orchestrator/campaign_status.hpp); the report replaces it at the end, with the model
    // finished.
    const std::vector<orch::BudgetPart> parts = planned_job_parts(c);
    options.on_progress = [&](nlohmann::json progress) {
      progress["progress"] = orch::progress_model_json(
          "jobs", int(ctx.service.store().counts(ctx.campaign_id).ended()), parts, 0, std::nullopt,
          false);
      ctx.service.set_progress(ctx.campaign_id, progress, ctx.stop);
    };
    nlohmann::json report = to_json(run_diagnosis(c, evaluator, options), c);
    report["progress"] =
        orch::progress_model_json("jobs", int(ctx.service.store().counts(ctx.campaign_id).ended()),
                                  parts, 0, std::nullopt, true);
    return report;
  };
  kind.report_html = [](const nlohmann::json& summary) { return report_html(summary); };
  return kind;
}

}  // namespace rockcal::diagnosis
