#include "orchestrator/slurm/states.hpp"

#include <sstream>
#include <stdexcept>
#include <vector>

namespace rockcal::orch::slurm {

Phase phase_of(std::string_view state) {
  auto end = state.find_first_of(" +");
  std::string_view s = state.substr(0, end);
  for (auto p : {"PENDING", "CONFIGURING", "REQUEUED", "REQUEUE_HOLD", "REQUEUE_FED",
                 "RESV_DEL_HOLD", "SPECIAL_EXIT"}) {
    if (s == p) return Phase::pending;
  }
  if (s == "COMPLETED") return Phase::completed;
  for (auto p :
       {"FAILED", "TIMEOUT", "NODE_FAIL", "OUT_OF_MEMORY", "BOOT_FAIL", "DEADLINE", "REVOKED"}) {
    if (s == p) return Phase::failed;
  }
  if (s == "CANCELLED") return Phase::cancelled;
  if (s == "PREEMPTED") return Phase::requeue;
  return Phase::running;
}

bool is_job_id(std::string_view s) {
  return !s.empty() && s.size() < 20 && s.find_first_not_of("0123456789") == std::string_view::npos;
}

namespace {

std::string trim(std::string s) {
  auto b = s.find_first_not_of(" \t\r\n");
  auto e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// Splits `line` at '|' into at most `n` fields (the last keeps any further '|').
std::vector<std::string> fields(const std::string& line, std::size_t n) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (out.size() + 1 < n) {
    auto bar = line.find('|', start);
    if (bar == std::string::npos) break;
    out.push_back(trim(line.substr(start, bar - start)));
    start = bar + 1;
  }
  out.push_back(trim(line.substr(start)));
  return out;
}

std::map<std::string, JobState> parse_lines(const std::string& out) {
  std::map<std::string, JobState> jobs;
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line)) {
    auto f = fields(line, 3);
    if (f.size() < 2 || !is_job_id(f[0])) continue;
    jobs[f[0]] = {f[1], f.size() > 2 ? f[2] : ""};
  }
  return jobs;
}

}  // namespace

std::map<std::string, JobState> parse_squeue(const std::string& out) {
  return parse_lines(out);
}

std::map<std::string, JobState> parse_sacct(const std::string& out) {
  // With --allocations sacct prints one line per job; without it, steps ("12.batch") too, which
  // parse_lines skips because their ids are not plain numbers.
  return parse_lines(out);
}

std::string parse_sbatch_id(const std::string& out) {
  std::string s = trim(out);
  auto semi = s.find(';');
  std::string id = trim(s.substr(0, semi));
  if (!is_job_id(id)) throw std::runtime_error("sbatch printed no job id: '" + s + "'");
  return id;
}

}  // namespace rockcal::orch::slurm
