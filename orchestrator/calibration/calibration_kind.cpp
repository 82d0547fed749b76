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

// How fast this driver's evaluations go, for a client's ETA: the search's and the fine runs'
// apart (a fine run costs tens of search evaluations). Evaluations the job cache answered at once
// (the replay of a restarted driver, points run before) count against the budget but not in the
// pace: they would make every later evaluation look nearly free.
class Pace {
 public:
  Pace() : start_(Clock::now()), last_(start_) {}

  void add(const EvaluationRecord& r) {
    const bool fine = r.phase.rfind("fine", 0) == 0;
    const Clock::time_point now = Clock::now();
    if (fine) ++fine_done_;
    if (!answered_by_cache(r)) {
      Kind& k = fine ? fine_ : search_;
      // A kind's first evaluation is timed from when the one before it (of either kind) ended:
      // the fine runs start as the search ends.
      if (k.times.empty()) k.since = last_;
      k.times.push_back(now);
    }
    last_ = now;
  }

  EvaluationPace pace() const { return {search_.per(), fine_.per(), fine_done_}; }

  nlohmann::json to_json() const {
    const auto per = search_.per();
    const auto fine = fine_.per();
    return {{"wall_seconds", seconds(Clock::now() - start_)},
            {"evaluations_timed", int(search_.times.size() + fine_.times.size())},
            {"seconds_per_evaluation", per ? nlohmann::json(*per) : nlohmann::json(nullptr)},
            {"seconds_per_fine_run", fine ? nlohmann::json(*fine) : nlohmann::json(nullptr)}};
  }

 private:
  using Clock = std::chrono::steady_clock;
  static double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

  struct Kind {
    Clock::time_point since;               // when the one before its first ended
    std::vector<Clock::time_point> times;  // when each timed evaluation ended
    // Per evaluation over the latest kWindow timed ones: the start batch runs its points side by
    // side, the search after it one by one, so the pace of the start would promise too much.
    std::optional<double> per() const {
      const int n = int(times.size());
      if (n > kWindow) return seconds(times.back() - times[n - 1 - kWindow]) / kWindow;
      if (n > 0) return seconds(times.back() - since) / n;
      return std::nullopt;
    }
  };

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
  Clock::time_point start_, last_;
  Kind search_, fine_;
  int fine_done_ = 0;
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
      live["progress"] = progress_model_json(history.size(), c, pace.pace(), false);
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
    report["progress"] = progress_model_json(report["evaluations"].get<std::size_t>(), c, {}, true);
    return report;
  };
  return kind;
}

}  // namespace rockcal::calibration
