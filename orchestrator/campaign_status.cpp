#include "orchestrator/campaign_status.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

namespace rockcal::orch {

bool is_terminal_job_state(const std::string& s) {
  return s == db::kSucceeded || s == db::kFailed || s == db::kCancelled;
}

std::string derive_state(const db::StateCounts& c, const db::CampaignRow& campaign) {
  const auto& driver = campaign.driver_status;
  bool driver_running = driver && *driver == "running";
  if (c.queued + c.running > 0 || driver_running) {
    bool started = c.running + c.succeeded + c.failed > 0;
    return started || driver_running ? "running" : "queued";
  }
  if (campaign.cancel_requested) return "cancelled";
  // A driver (calibration, diagnosis) takes a failed job as a data point (a run without a peak is
  // one): its own end decides, and the failed jobs stay counted in the progress.
  if (driver && *driver == "done") return "succeeded";
  if (c.failed > 0 || (driver && *driver == "failed")) return "failed";
  if (c.cancelled > 0) return "cancelled";
  return "succeeded";
}

namespace {

// A driver adds jobs as it goes, so the share of its jobs done can fall: its own progress, when
// its summary states one, is the campaign's. A calibration states its fraction
// (orchestrator/calibration/progress.hpp); a diagnosis its phase: step of steps, the jobs done
// before the phase began and the runs it plans (the phase's share of its runs done so far). Both
// only grow.
std::optional<double> driver_fraction(const db::CampaignRow& campaign,
                                      const db::StateCounts& counts) {
  if (!campaign.summary || campaign.driver_status.value_or("") != "running") return std::nullopt;
  const nlohmann::json s = nlohmann::json::parse(*campaign.summary, nullptr, false);
  if (!s.is_object()) return std::nullopt;
  const nlohmann::json model = s.value("progress", nlohmann::json());
  if (model.is_object() && model.value("fraction", nlohmann::json()).is_number())
    return model["fraction"].get<double>();
  const nlohmann::json step = s.value("step", nlohmann::json());
  const nlohmann::json steps = s.value("steps", nlohmann::json());
  const nlohmann::json before = s.value("jobs_done_before", nlohmann::json());
  if (!step.is_number() || !steps.is_number() || steps.get<double>() <= 0 || !before.is_number())
    return std::nullopt;
  const double runs = s.value("runs", 0.0);
  const double done = double(counts.succeeded + counts.failed + counts.cancelled);
  const double in_phase =
      runs > 0 ? std::clamp((done - before.get<double>()) / runs, 0.0, 1.0) : 0.0;
  return (step.get<double>() - 1.0 + in_phase) / steps.get<double>();
}

}  // namespace

CampaignStatus campaign_status(db::Store& store, const db::CampaignRow& campaign, int workers) {
  CampaignStatus s;
  s.counts = store.counts(campaign.id);
  s.state = derive_state(s.counts, campaign);
  double running_done = 0;
  if (s.counts.running > 0) {
    for (const auto& j : store.running_jobs(campaign.id)) running_done += j.progress.value_or(0);
  }
  auto total = s.counts.total();
  double done = static_cast<double>(s.counts.succeeded + s.counts.failed + s.counts.cancelled);
  s.fraction = total > 0 ? (done + running_done) / static_cast<double>(total) : 0.0;
  if (const auto f = driver_fraction(campaign, s.counts)) s.fraction = *f;
  if (s.counts.queued + s.counts.running == 0) {
    s.eta_seconds = 0.0;
    return s;
  }
  // Mean run time of this campaign's jobs, else of every job run so far.
  auto d = store.durations(campaign.id);
  if (d.count == 0) d = store.durations();
  if (d.count == 0) return s;
  double mean = d.sum_seconds / static_cast<double>(d.count);
  double remaining_jobs = static_cast<double>(s.counts.queued + s.counts.running) - running_done;
  double parallel = static_cast<double>(std::max<std::int64_t>(
      1, std::min<std::int64_t>(workers, s.counts.queued + s.counts.running)));
  s.eta_seconds = remaining_jobs * mean / parallel;
  return s;
}

}  // namespace rockcal::orch
