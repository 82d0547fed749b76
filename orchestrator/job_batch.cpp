#include "orchestrator/job_batch.hpp"

#include <map>
#include <string>

namespace rockcal::orch {

std::optional<std::vector<JobOutcome>> run_batch(JobService& service, std::int64_t campaign_id,
                                                 const std::vector<nlohmann::json>& jobs,
                                                 std::stop_token stop) {
  // nlohmann::json objects keep keys sorted, so dump() is one key per spec.
  std::map<std::string, std::int64_t> job_of_spec;
  std::vector<std::int64_t> ids;
  for (const nlohmann::json& job : jobs) {
    auto [it, fresh] = job_of_spec.try_emplace(job.dump(), 0);
    if (fresh) it->second = service.submit_job(campaign_id, job, stop);
    if (stop.stop_requested()) return std::nullopt;  // perhaps before the job was stored
    ids.push_back(it->second);
  }
  std::map<std::int64_t, JobOutcome> outcome_of;
  for (const auto& [spec, id] : job_of_spec) {
    JobOutcome outcome = service.wait_job(id, stop);
    if (stop.stop_requested() || outcome.state == "cancelled") return std::nullopt;
    outcome_of.emplace(id, std::move(outcome));
  }
  std::vector<JobOutcome> outcomes;
  for (std::int64_t id : ids) outcomes.push_back(outcome_of.at(id));
  return outcomes;
}

}  // namespace rockcal::orch
