#include "orchestrator/job_runner.hpp"

namespace rockcal::orch {

std::optional<std::vector<Ensemble>> run_ensembles(
    JobRunner& runner, const std::vector<std::vector<nlohmann::json>>& groups) {
  std::vector<nlohmann::json> jobs;
  for (const auto& group : groups) jobs.insert(jobs.end(), group.begin(), group.end());
  std::optional<std::vector<Realisation>> runs = runner.run(jobs);
  if (!runs) return std::nullopt;
  std::vector<Ensemble> ensembles;
  std::size_t next = 0;
  for (const auto& group : groups) {
    std::vector<Realisation> members;
    for (std::size_t k = 0; k < group.size(); ++k) members.push_back(std::move((*runs)[next++]));
    ensembles.push_back(make_ensemble(std::move(members)));
  }
  return ensembles;
}

}  // namespace rockcal::orch
