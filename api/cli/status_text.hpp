// What `rockcal status` prints for a campaign (GET /api/v1/campaigns/{id}): a progress line while
// it runs and a short summary once it has ended, each by kind, and the pacing of the line when the
// output is not a terminal.
#pragma once

#include <chrono>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace rockcal::api {

// A campaign's line from its driver's progress model (orchestrator/progress_model.hpp), while it
// runs and once its report carries the finished model: "campaign 3 running: 12 of 40 evaluations
// done (+2 seed re-runs), best misfit 0.0123 at F_r0 = 40.1, F_s0 = 89.7, 2 jobs running, ETA
// 5m20s (full budget)" (the best misfit a calibration's); a diagnosis adds its phase: "  [2/4
// budget]". Campaigns without a model (a sweep) get status_line().
std::string progress_line(const nlohmann::json& campaign);

// ", best misfit 0.0123 at F_r0 = 40.1, F_s0 = 89.7": a calibration summary's best evaluation so
// far, or "" before one has a misfit.
std::string best_misfit_text(const nlohmann::json& summary);

// The end of a campaign for a reader: a calibration's verdict, strengths, loads against targets
// and budget (calibration_text.hpp); a diagnosis's verdict tables (diagnosis_text.hpp); a sweep's
// job counts. At most ~30 lines; the JSON stays available with `rockcal status ID --json`.
std::string summary_text(const nlohmann::json& campaign);

// "4m10s" for 250 seconds.
std::string duration_text(double seconds);

// For output that is not a terminal (CI logs, a piped quick start): a line is worth printing when
// it differs from the last one printed and `interval` has passed since then, so a log gets one line
// per change at most every few seconds instead of one a second.
class LinePacer {
 public:
  using Clock = std::chrono::steady_clock;
  explicit LinePacer(Clock::duration interval) : interval_(interval) {}
  // True (and remembered as printed) when `line` should be printed at `now`.
  bool due(const std::string& line, Clock::time_point now);

 private:
  Clock::duration interval_;
  std::string last_;
  std::optional<Clock::time_point> printed_at_;
};

}  // namespace rockcal::api
