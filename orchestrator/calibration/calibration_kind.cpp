#include "orchestrator/calibration/calibration_kind.hpp"

#include <algorithm>
#include <chrono>
#include <optional>
#include <vector>

#include "orchestrator/calibration/campaign.hpp"
#include "orchestrator/calibration/driver.hpp"
#include "orchestrator/calibration/progress.hpp"
#include "orchestrator/calibration/runner_evaluator.hpp"
#include "orchestrator/job_service.hpp"
#include "orchestrator/pool_runner.hpp"
#include "orchestrator/request_error.hpp"

namespace rockcal::calibration {
namespace {

// How fast this driver's evaluations go, for a client's ETA. Evaluations the job cache answered
// at once (the replay of a restarted driver, points run before) count against the budget but not
// in the pace: they would make every later evaluation look nearly free.
class Pace {
 public:
  Pace() : start_(Clock::now()) {}

  void add(const EvaluationRecord& r) {
    if (answered_by_cache(r)) return;
    times_.push_back(Clock::now());
  }

  // Per evaluation over the latest kWindow timed ones: the start batch runs its points side by
  // side, the search after it one by one, so the pace of the start would promise too much.
  std::optional<double> seconds_per_evaluation() const {
    const int n = int(times_.size());
    if (n > kWindow) return seconds(times_.back() - times_[n - 1 - kWindow]) / kWindow;
    if (n > 0) return seconds(times_.back() - start_) / n;
    return std::nullopt;
  }

  nlohmann::json to_json() const {
    const auto per = seconds_per_evaluation();
    return {{"wall_seconds", seconds(Clock::now() - start_)},
            {"evaluations_timed", int(times_.size())},
            {"seconds_per_evaluation", per ? nlohmann::json(*per) : nlohmann::json(nullptr)}};
  }

 private:
  using Clock = std::chrono::steady_clock;
  static double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

  static bool answered_by_cache(const EvaluationRecord& r) {
    if (!r.uct || !r.btt) return false;
    for (const orch::Ensemble* e : {&*r.uct, &*r.btt}) {
      for (const orch::Realisation& run : e->realisations) {
        if (!run.cached) return false;
      }
    }
    return true;
  }

  static constexpr int kWindow = 8;
  Clock::time_point start_;
  std::vector<Clock::time_point> times_;  // when each timed evaluation ended
};

}  // namespace

orch::CampaignKind calibration_kind() {
  orch::CampaignKind kind;
  kind.name = "calibration";
  kind.plan = [](const nlohmann::json& request, const orch::Limits&) {
    const CalibrationCampaign c = parse_calibration_campaign(request);
    return orch::CampaignPlan{c.name, {}};
  };
  // Runs in the service's driver thread; a restart after a crash runs it again from the stored
  // request, and the job cache replays the finished evaluations.
  kind.driver = [](orch::DriverContext& ctx) {
    const CalibrationCampaign c = parse_calibration_campaign(ctx.request);
    orch::PoolRunner pool(ctx.service, ctx.campaign_id, ctx.stop);
    RunnerEvaluator evaluator(pool, c.job_template);
    Pace pace;
    // While it runs, the campaign's summary is the history so far, with the budget and the pace
    // a client needs for its progress line (from the start, so the budget shows before the first
    // evaluation ends); the report replaces it at the end.
    std::vector<EvaluationRecord> history;
    nlohmann::json stiffness = nullptr;
    auto publish = [&] {
      nlohmann::json live = progress_json(history, c);
      live["stiffness"] = stiffness;
      live["scatter_runs"] = seed_reruns(c);
      live["pace"] = pace.to_json();
      live["progress"] =
          progress_model_json(history.size(), c, pace.seconds_per_evaluation(), false);
      ctx.service.set_progress(ctx.campaign_id, live, ctx.stop);
    };
    publish();
    auto on_evaluation = [&](const EvaluationRecord& record) {
      history.push_back(record);
      pace.add(record);
      publish();
    };
    auto on_stiffness = [&](const StiffnessResult& result) {
      stiffness = to_json(result, c);
      publish();
    };
    nlohmann::json report = to_json(
        run_calibration(c, evaluator,
                        {ctx.stop, on_evaluation, ctx.service.config().workers, on_stiffness}),
        c);
    report["pace"] = pace.to_json();
    report["progress"] =
        progress_model_json(report["evaluations"].get<std::size_t>(), c, std::nullopt, true);
    return report;
  };
  return kind;
}

}  // namespace rockcal::calibration
