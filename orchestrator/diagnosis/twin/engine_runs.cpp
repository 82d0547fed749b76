#include "orchestrator/diagnosis/twin/engine_runs.hpp"

#include <fstream>
#include <map>
#include <stdexcept>
#include <thread>

#include "orchestrator/job_files.hpp"
#include "orchestrator/local_executor.hpp"

namespace rockcal::diagnosis {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string failure(const fs::path& dir, const std::string& what) {
  return "engine run " + dir.string() + " failed (" + what + "); end of its log:\n" +
         orch::tail_file(dir / "log", 15, 4000);
}

json read_result(const fs::path& dir, const orch::ExitStatus& status) {
  if (status.signal != 0 || status.exit_code != 0) {
    throw std::runtime_error(failure(dir, status.describe()));
  }
  const auto text = orch::read_text(dir / "result.json");
  if (!text) throw std::runtime_error(failure(dir, "no result.json"));
  json result = json::parse(*text);
  // The service's rule: a run that ended without a peak failed, whatever load it reached.
  if (auto why = orch::no_peak_reason(result))
    throw std::runtime_error(failure(dir, "no peak: " + *why));
  return result;
}

}  // namespace

std::vector<json> EngineRunner::run(const std::vector<json>& jobs) {
  orch::LocalExecutorConfig local;
  local.engine = config_.engine;
  local.ranks = 0;
  local.grace = std::chrono::milliseconds(2000);
  orch::LocalExecutor executor(local);
  std::vector<json> results(jobs.size());
  std::vector<fs::path> dirs;
  for (const json& job : jobs) {
    const fs::path dir = fs::absolute(config_.work_dir / ("job-" + std::to_string(next_++)));
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "job.json") << job.dump(2) << "\n";
    dirs.push_back(dir);
  }
  std::map<std::string, std::size_t> running;  // handle -> job index
  std::size_t next = 0;
  try {
    while (next < jobs.size() || !running.empty()) {
      while (next < jobs.size() && int(running.size()) < std::max(1, config_.parallel)) {
        const fs::path& dir = dirs[next];
        const orch::LaunchRequest request{
            dir, dir / "log", {"run", (dir / "job.json").string(), "--out", dir.string()}};
        running.emplace(executor.launch(request), next++);
      }
      for (auto it = running.begin(); it != running.end();) {
        const orch::ExitStatus status = executor.poll(it->first);
        if (!status.finished) {
          ++it;
          continue;
        }
        results[it->second] = read_result(dirs[it->second], status);
        it = running.erase(it);
      }
      if (!running.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  } catch (...) {
    for (const auto& [handle, index] : running) executor.cancel(handle);
    throw;
  }
  return results;
}

}  // namespace rockcal::diagnosis
