#include "api/server/metrics.hpp"

#include <map>

#include "api/server/http_util.hpp"

namespace rockcal::api {

namespace {

std::string executor_metrics(orch::JobService& service) {
  const std::string current = service.executor().name();
  // Jobs waiting for a worker will be run by this server's executor.
  std::map<std::string, db::ExecutorCounts> by_executor{{current, {current}}};
  for (const auto& c : service.store().executor_counts()) {
    auto& e = by_executor[c.executor.empty() ? current : c.executor];
    e.executor = c.executor.empty() ? current : c.executor;
    e.waiting += c.waiting;
    e.pending += c.pending;
    e.running += c.running;
  }
  std::string out;
  auto gauge = [&](const char* name, const char* help, auto value) {
    out += std::string("# HELP ") + name + " " + help + "\n# TYPE " + name + " gauge\n";
    for (const auto& [executor, c] : by_executor) {
      out +=
          std::string(name) + "{executor=\"" + executor + "\"} " + std::to_string(value(c)) + "\n";
    }
  };
  gauge("rockcal_executor_queue_depth", "Jobs waiting for a worker of the executor.",
        [](const db::ExecutorCounts& c) { return c.waiting; });
  gauge("rockcal_executor_running", "Jobs running under the executor.",
        [](const db::ExecutorCounts& c) { return c.running; });
  gauge("rockcal_executor_pending",
        "Jobs submitted and waiting in the executor's scheduler "
        "(PENDING in Slurm).",
        [](const db::ExecutorCounts& c) { return c.pending; });
  out +=
      "# HELP rockcal_executor_failures_total Failed attempts since the server started, by "
      "reason.\n# TYPE rockcal_executor_failures_total counter\n";
  for (const auto& [reason, n] : service.failures().snapshot()) {
    out += "rockcal_executor_failures_total{executor=\"" + current + "\",reason=\"" + reason +
           "\"} " + std::to_string(n) + "\n";
  }
  return out;
}

}  // namespace

std::string metrics_text(orch::JobService& service, int workers) {
  db::Store& store = service.store();
  auto c = store.counts();
  std::string out;
  out += "# HELP rockcal_jobs Jobs by state.\n# TYPE rockcal_jobs gauge\n";
  for (auto [state, n] : {std::pair{"queued", c.queued},
                          {"running", c.running},
                          {"succeeded", c.succeeded},
                          {"failed", c.failed},
                          {"cancelled", c.cancelled}}) {
    out += std::string("rockcal_jobs{state=\"") + state + "\"} " + std::to_string(n) + "\n";
  }
  out += "# HELP rockcal_jobs_cached Succeeded jobs answered from the store without running.\n";
  out += "# TYPE rockcal_jobs_cached gauge\nrockcal_jobs_cached " + std::to_string(c.cached) + "\n";
  out += "# HELP rockcal_queue_length Jobs waiting for a worker.\n";
  out +=
      "# TYPE rockcal_queue_length gauge\nrockcal_queue_length " + std::to_string(c.queued) + "\n";
  out += "# HELP rockcal_workers Jobs run at once.\n";
  out += "# TYPE rockcal_workers gauge\nrockcal_workers " + std::to_string(workers) + "\n";
  out += "# HELP rockcal_campaigns Campaigns stored.\n";
  out += "# TYPE rockcal_campaigns gauge\nrockcal_campaigns " +
         std::to_string(store.campaign_count()) + "\n";

  const std::vector<double> bounds = {1, 5, 15, 60, 300, 900, 3600, 14400};
  auto buckets = store.duration_buckets(bounds);
  auto d = store.durations();
  out += "# HELP rockcal_job_duration_seconds Run time of succeeded jobs.\n";
  out += "# TYPE rockcal_job_duration_seconds histogram\n";
  for (std::size_t i = 0; i < bounds.size(); ++i) {
    out += "rockcal_job_duration_seconds_bucket{le=\"" + number_text(bounds[i]) + "\"} " +
           std::to_string(buckets[i]) + "\n";
  }
  out += "rockcal_job_duration_seconds_bucket{le=\"+Inf\"} " + std::to_string(d.count) + "\n";
  out += "rockcal_job_duration_seconds_sum " + number_text(d.sum_seconds) + "\n";
  out += "rockcal_job_duration_seconds_count " + std::to_string(d.count) + "\n";
  out += executor_metrics(service);
  out +=
      "# HELP rockcal_storage_faults_total Store writes that failed for a storage fault (and were "
      "retried or answered 503/507) since the server started, by kind.\n"
      "# TYPE rockcal_storage_faults_total counter\n";
  const auto faults = store.health().counts();
  for (const char* kind : {"busy", "full", "io"}) {
    const auto it = faults.find(kind);
    out += std::string("rockcal_storage_faults_total{kind=\"") + kind + "\"} " +
           std::to_string(it == faults.end() ? 0 : it->second) + "\n";
  }
  return out;
}

}  // namespace rockcal::api
