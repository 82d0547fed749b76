#include "orchestrator/campaign_status.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "orchestrator/progress_model.hpp"

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

// A driver adds jobs as it goes, so the share of its jobs done can fall: its progress model
// (orchestrator/progress_model.hpp), when its summary carries one, is the campaign's. A
// calibration states its model whole (evaluations of its budget, its pace's ETA); a diagnosis
// states the jobs it plans by phase, and its jobs done are counted here, as the model is read,
// with the ETA at `seconds_per_job`. Both count done against a budget fixed up front, so their
// fraction only grows.
std::optional<nlohmann::json> driver_model(const db::CampaignRow& campaign,
                                           const db::StateCounts& counts,
                                           std::optional<double> seconds_per_job) {
  if (!campaign.summary || campaign.driver_status.value_or("") != "running") return std::nullopt;
  const nlohmann::json s = nlohmann::json::parse(*campaign.summary, nullptr, false);
  if (!s.is_object()) return std::nullopt;
  const nlohmann::json model = s.value("progress", nlohmann::json());
  if (!model.is_object() || !model.value("fraction", nlohmann::json()).is_number())
    return std::nullopt;
  if (model.value("unit", "") != "jobs") return model;
  return progress_model_json("jobs", int(counts.ended()), budget_parts(model), 0, seconds_per_job,
                             false);
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
  double done = static_cast<double>(s.counts.ended());
  s.fraction = total > 0 ? (done + running_done) / static_cast<double>(total) : 0.0;
  // Mean run time of this campaign's jobs, else of every job run so far (for a campaign still
  // at work).
  const bool working =
      s.counts.queued + s.counts.running > 0 || campaign.driver_status.value_or("") == "running";
  db::DurationStats d;
  if (working) d = store.durations(campaign.id);
  if (working && d.count == 0) d = store.durations();
  const std::optional<double> mean =
      d.count > 0 ? std::optional<double>(d.sum_seconds / static_cast<double>(d.count))
                  : std::nullopt;
  const std::optional<double> seconds_per_job =
      mean ? std::optional<double>(*mean / std::max(1, workers)) : std::nullopt;
  if (auto model = driver_model(campaign, s.counts, seconds_per_job)) {
    s.fraction = (*model)["fraction"].get<double>();
    s.model = std::move(*model);
  }
  if (s.counts.queued + s.counts.running == 0) {
    s.eta_seconds = 0.0;
    return s;
  }
  if (!mean) return s;
  double remaining_jobs = static_cast<double>(s.counts.queued + s.counts.running) - running_done;
  double parallel = static_cast<double>(std::max<std::int64_t>(
      1, std::min<std::int64_t>(workers, s.counts.queued + s.counts.running)));
  s.eta_seconds = remaining_jobs * *mean / parallel;
  return s;
}

}  // namespace rockcal::orch
