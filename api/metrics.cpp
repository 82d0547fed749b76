#include "api/metrics.hpp"

#include "api/http_util.hpp"

namespace rockcal::api {

std::string metrics_text(db::Store& store, int workers) {
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
  return out;
}

}  // namespace rockcal::api
