#include "orchestrator/calibration/calibration_kind.hpp"

#include "orchestrator/calibration/campaign.hpp"
#include "orchestrator/calibration/driver.hpp"
#include "orchestrator/calibration/pool_evaluator.hpp"
#include "orchestrator/request_error.hpp"

namespace rockcal::calibration {
namespace {

CalibrationCampaign parse_request(const nlohmann::json& request) {
  try {
    return parse_calibration_campaign(request);
  } catch (const CampaignError& e) {
    throw orch::RequestError(e.field, e.what());
  }
}

}  // namespace

orch::CampaignKind calibration_kind() {
  orch::CampaignKind kind;
  kind.name = "calibration";
  kind.plan = [](const nlohmann::json& request, const orch::Limits&) {
    const CalibrationCampaign c = parse_request(request);
    return orch::CampaignPlan{c.name, {}};
  };
  // Runs in the service's driver thread; a restart after a crash runs it again from the stored
  // request, and the job cache replays the finished evaluations.
  kind.driver = [](orch::DriverContext& ctx) {
    const CalibrationCampaign c = parse_request(ctx.request);
    PoolEvaluator evaluator(ctx.service, ctx.campaign_id, c.job_template, ctx.stop);
    // While it runs, the campaign's summary is the history so far; the report replaces it at the
    // end.
    std::vector<EvaluationRecord> history;
    auto on_evaluation = [&](const EvaluationRecord& record) {
      history.push_back(record);
      ctx.service.store().set_driver_status(ctx.campaign_id, "running",
                                            progress_json(history, c).dump());
    };
    return to_json(run_calibration(c, evaluator, {ctx.stop, on_evaluation}), c);
  };
  return kind;
}

}  // namespace rockcal::calibration
