#include "orchestrator/campaign_status.hpp"

#include <algorithm>

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
