#include "orchestrator/diagnosis/diagnosis_kind.hpp"

#include "orchestrator/diagnosis/pipeline/driver.hpp"
#include "orchestrator/diagnosis/pipeline/grid.hpp"
#include "orchestrator/diagnosis/pipeline/jobs.hpp"
#include "orchestrator/diagnosis/pipeline/pool_evaluator.hpp"
#include "orchestrator/diagnosis/report/report.hpp"
#include "orchestrator/request_error.hpp"

namespace rockcal::diagnosis {

std::size_t planned_jobs(const DiagnosisCampaign& c) {
  const std::size_t grid = std::size_t(grid_points(c));
  const std::size_t seeds = c.budget.seeds.size();
  // Measured at the base model's first fit and, if it moved, again at its confirmed fit.
  const std::size_t budget = 2 * budget_offsets(c.budget.points).size() *
                             budget_runs_per_point(c.budget, c.dataset.origin);
  const std::size_t confirm = (1 + std::size_t(c.confirm)) * (1 + std::size_t(c.refine) + seeds);
  return (grid + budget + confirm) * plan_runs(c.targets).runs.size();
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
                      " per campaign: a smaller grid, grid.design \"local\" or fewer effects");
    }
    return orch::CampaignPlan{c.name, {}};
  };
  // Runs in the service's driver thread; a restart after a crash runs it again from the stored
  // request, and the job cache replays the finished runs.
  kind.driver = [](orch::DriverContext& ctx) {
    const DiagnosisCampaign c = parse_diagnosis_campaign(ctx.request);
    PoolEvaluator evaluator(ctx.service, ctx.campaign_id, c.job_template, c.targets, ctx.stop);
    DiagnosisOptions options;
    options.stop = ctx.stop;
    // While it runs, the summary says which phase it is in; the report replaces it at the end.
    // With the jobs done before the phase began, the campaign's progress counts the phase's own
    // (orchestrator/campaign_status.hpp).
    options.on_progress = [&](nlohmann::json progress) {
      const db::StateCounts done = ctx.service.store().counts(ctx.campaign_id);
      progress["jobs_done_before"] = done.succeeded + done.failed + done.cancelled;
      ctx.service.set_progress(ctx.campaign_id, progress, ctx.stop);
    };
    return to_json(run_diagnosis(c, evaluator, options), c);
  };
  kind.report_html = [](const nlohmann::json& summary) { return report_html(summary); };
  return kind;
}

}  // namespace rockcal::diagnosis
