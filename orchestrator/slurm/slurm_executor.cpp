#include "orchestrator/slurm/slurm_executor.hpp"

#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "orchestrator/command.hpp"

namespace rockcal::orch::slurm {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

std::string job_name(const fs::path& job_dir) {
  return "rockcal-" + job_dir.filename().string();
}

std::vector<std::string> sbatch_command(const SlurmConfig& c, const LaunchRequest& r) {
  std::vector<std::string> argv = {"sbatch", "--parsable", "--job-name=" + job_name(r.job_dir),
                                   // Unique per server (the absolute job directory): a restarted
                                   // server finds a job whose id it never stored by it.
                                   "--comment=" + r.job_dir.string(),
                                   "--chdir=" + r.job_dir.string(),
                                   "--output=" + r.log_file.string(), "--open-mode=append",
                                   "--ntasks=" + std::to_string(std::max(1, c.ranks))};
  if (!c.partition.empty()) argv.push_back("--partition=" + c.partition);
  if (!c.account.empty()) argv.push_back("--account=" + c.account);
  if (!c.time_limit.empty()) argv.push_back("--time=" + c.time_limit);
  argv.push_back((r.job_dir / kBatchScriptFile).string());
  return argv;
}

std::string first_line(const std::string& s) {
  auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  auto e = s.find('\n', b);
  return s.substr(b, e == std::string::npos ? std::string::npos : e - b);
}

std::string command_failure(const std::vector<std::string>& argv, const CommandResult& r) {
  std::string why = !r.error.empty() ? r.error : "exit code " + std::to_string(r.exit_code);
  std::string said = first_line(r.err);
  return argv[0] + " failed (" + why + ")" + (said.empty() ? "" : ": " + said);
}

std::optional<int> read_marker(const fs::path& dir) {
  if (dir.empty()) return std::nullopt;
  std::ifstream in(dir / kExitStatusFile);
  int code = 0;
  if (in >> code) return code;
  return std::nullopt;
}

std::optional<std::string> read_id_file(const fs::path& dir) {
  std::ifstream in(dir / kSlurmIdFile);
  std::string id;
  if (in >> id && is_job_id(id)) return id;
  return std::nullopt;
}

std::string join_ids(const std::map<std::string, JobState>& skip,
                     const std::vector<std::string>& ids) {
  std::string out;
  for (const auto& id : ids) {
    if (skip.count(id)) continue;
    out += (out.empty() ? "" : ",") + id;
  }
  return out;
}

}  // namespace

std::string batch_script(const SlurmConfig& config, const LaunchRequest& request) {
  const std::string marker = (request.job_dir / kExitStatusFile).string();
  std::string run = "srun ";
  if (!config.srun_mpi.empty()) run += "--mpi=" + shell_quote(config.srun_mpi) + " ";
  run += shell_quote(config.engine);
  for (const auto& a : request.engine_args) {
    run += ' ';
    run += shell_quote(a);
  }
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# Written by rockcal serve and submitted with\n"
    << "#   " << command_text(sbatch_command(config, request)) << "\n"
    << "# Runs the engine, then writes the completion marker " << kExitStatusFile
    << " with its exit status:\n"
    << "# finished jobs leave squeue within minutes and sacct may be off.\n"
    << "rm -f " << shell_quote(marker) << "\n"
    << run << "\n"
    << "status=$?\n"
    << "printf '%s\\n' \"$status\" > " << shell_quote(marker + ".tmp") << " && mv -f "
    << shell_quote(marker + ".tmp") << " " << shell_quote(marker) << "\n"
    << "exit \"$status\"\n";
  return s.str();
}

ExitStatus status_from(const std::string& handle, const Observation& seen) {
  ExitStatus s;
  auto by_run = [&](int code) {
    s.finished = true;
    s.ending = Ending::run;
    s.exit_code = code;
    return s;
  };
  if (seen.marker_exit == 0) return by_run(0);
  if (!seen.slurm) {
    if (seen.marker_exit) return by_run(*seen.marker_exit);
    s.finished = true;
    s.ending = Ending::failed;
    s.scheduler_state = "LOST";
    s.reason = "Slurm job " + handle +
               " ended without writing its completion marker, and neither squeue nor sacct "
               "knows it any more";
    return s;
  }
  const auto& st = *seen.slurm;
  std::string state = st.state.substr(0, st.state.find_first_of(" +"));
  std::string detail = st.reason.empty() || st.reason == "None" ? "" : " (" + st.reason + ")";
  switch (phase_of(st.state)) {
    case Phase::pending:
      s.pending = true;
      return s;
    case Phase::running:
      return s;
    case Phase::completed:
      return by_run(seen.marker_exit.value_or(0));
    case Phase::failed:
      // FAILED after the script wrote its marker is the engine's own exit (e.g. 2: invalid spec,
      // never retried); any other failure state is Slurm's verdict, whatever the script wrote.
      if (state == "FAILED" && seen.marker_exit) return by_run(*seen.marker_exit);
      s.finished = true;
      s.ending = Ending::failed;
      s.scheduler_state = state;
      s.reason = "Slurm job " + handle + " ended " + state + detail;
      return s;
    case Phase::cancelled:
      s.finished = true;
      s.ending = Ending::cancelled;
      s.scheduler_state = state;
      s.reason = "Slurm job " + handle + " was cancelled in Slurm (" + st.state + ")";
      return s;
    case Phase::requeue:
      s.finished = true;
      s.ending = Ending::requeue;
      s.scheduler_state = state;
      s.reason = "Slurm job " + handle + " was " + state + detail + "; the job is queued again";
      return s;
  }
  return s;
}

std::string SlurmExecutor::launch(const LaunchRequest& request) {
  const fs::path script = request.job_dir / kBatchScriptFile;
  {
    std::ofstream out(script);
    out << batch_script(config_, request);
    if (!out) throw std::runtime_error("cannot write " + script.string());
  }
  fs::permissions(script, fs::perms::owner_all | fs::perms::group_read | fs::perms::others_read);
  fs::remove(request.job_dir / kExitStatusFile);
  fs::remove(request.job_dir / kSlurmIdFile);
  auto argv = sbatch_command(config_, request);
  auto r = run_command(argv);
  std::string id;
  if (r.ok()) {
    id = parse_sbatch_id(r.out);
  } else {
    // sbatch may have timed out after slurmctld took the job: never submit it a second time.
    std::optional<std::string> found;
    try {
      found = find_by_directory(request.job_dir);
    } catch (const std::exception&) {
    }
    if (!found) throw std::runtime_error(command_failure(argv, r));
    id = *found;
  }
  { std::ofstream(request.job_dir / kSlurmIdFile) << id << "\n"; }
  std::lock_guard lock(mutex_);
  Watched w{request.job_dir, Clock::now(), {}};
  w.last.pending = true;
  watched_[id] = w;
  return id;
}

void SlurmExecutor::refresh(std::chrono::milliseconds max_age) {
  auto started = Clock::now();
  if (queries_ > 0 && started - last_query_ < max_age) return;
  if (watched_.empty()) return;
  std::vector<std::string> ids;
  for (const auto& [id, w] : watched_) ids.push_back(id);
  std::map<std::string, JobState> known;
  std::vector<std::string> squeue = {"squeue", "--noheader", "--states=all",
                                     "--jobs=" + join_ids({}, ids), "--format=%i|%T|%r"};
  auto r = run_command(squeue);
  ++queries_;
  last_query_ = started;
  if (r.ok()) {
    known = parse_squeue(r.out);
  } else if (r.err.find("Invalid job id") == std::string::npos) {
    // slurmctld unreachable or similar: say nothing new about any job until it answers again.
    last_query_ok_ = false;
    if (started - last_warning_ > std::chrono::minutes(1) || last_warning_ == Clock::time_point{}) {
      std::cerr << "rockcal: " << command_failure(squeue, r) << "\n";
      last_warning_ = started;
    }
    return;
  }
  // Jobs squeue has forgotten (MinJobAge): sacct, if accounting is on, still knows how they ended.
  std::string missing = join_ids(known, ids);
  if (!missing.empty()) {
    std::vector<std::string> sacct = {
        "sacct",         "--noheader",        "--parsable2",
        "--allocations", "--jobs=" + missing, "--format=JobIDRaw,State,ExitCode"};
    auto a = run_command(sacct);
    ++queries_;
    if (a.ok()) {
      for (auto& [id, st] : parse_sacct(a.out)) known.emplace(id, st);
    }
  }
  known_ = std::move(known);
  last_query_ok_ = true;
}

ExitStatus SlurmExecutor::status_locked(const std::string& handle,
                                        std::chrono::milliseconds max_age) {
  auto it = watched_.find(handle);
  if (it == watched_.end()) {
    Watched w{{}, Clock::now(), {}};
    it = watched_.emplace(handle, w).first;
  }
  Observation seen;
  seen.marker_exit = read_marker(it->second.dir);
  if (seen.marker_exit != 0) {
    refresh(max_age);
    // Only a query that started after the job was submitted (or adopted) can speak for it.
    if (!last_query_ok_ || last_query_ < it->second.since) return it->second.last;
    if (auto k = known_.find(handle); k != known_.end()) seen.slurm = k->second;
  }
  ExitStatus s = status_from(handle, seen);
  if (s.finished) {
    watched_.erase(it);
  } else {
    it->second.last = s;
  }
  return s;
}

ExitStatus SlurmExecutor::poll(const std::string& handle) {
  if (!is_job_id(handle)) throw std::invalid_argument("bad Slurm job id '" + handle + "'");
  std::lock_guard lock(mutex_);
  return status_locked(handle, config_.query_interval);
}

ExitStatus SlurmExecutor::cancel(const std::string& handle) {
  ExitStatus s = poll(handle);
  if (s.finished) return s;
  std::vector<std::string> argv = {"scancel", handle};
  auto r = run_command(argv);
  if (!r.ok()) std::cerr << "rockcal: " << command_failure(argv, r) << "\n";
  auto deadline = Clock::now() + config_.cancel_timeout;
  // Shorter than the query interval: a cancel is waited for, and one query answers every job
  // being cancelled at the same time (a whole campaign).
  auto step = std::min(config_.query_interval, std::chrono::milliseconds(500));
  while (Clock::now() < deadline) {
    std::this_thread::sleep_for(step);
    std::lock_guard lock(mutex_);
    s = status_locked(handle, step);
    if (s.finished) return s;
  }
  std::lock_guard lock(mutex_);
  watched_.erase(handle);
  s = {};
  s.finished = true;
  s.ending = Ending::failed;
  s.scheduler_state = "CANCEL_TIMEOUT";
  s.reason = "Slurm job " + handle + " still not ended " +
             std::to_string(config_.cancel_timeout.count() / 1000) + " s after scancel";
  return s;
}

std::optional<std::string> SlurmExecutor::find_by_directory(const fs::path& job_dir) {
  std::vector<std::string> argv = {"squeue", "--noheader", "--states=all",
                                   "--name=" + job_name(job_dir), "--format=%i|%k"};
  auto r = run_command(argv);
  {
    std::lock_guard lock(mutex_);
    ++queries_;
  }
  if (!r.ok()) throw std::runtime_error(command_failure(argv, r));
  std::istringstream in(r.out);
  std::string line;
  while (std::getline(in, line)) {
    auto bar = line.find('|');
    if (bar == std::string::npos) continue;
    std::string id = line.substr(0, bar), comment = line.substr(bar + 1);
    while (!comment.empty() && (comment.back() == ' ' || comment.back() == '\r'))
      comment.pop_back();
    if (is_job_id(id) && comment == job_dir.string()) return id;
  }
  return std::nullopt;
}

std::optional<std::string> SlurmExecutor::reattach(const std::optional<std::string>& handle,
                                                   const fs::path& job_dir) {
  std::optional<std::string> id;
  if (handle && is_job_id(*handle)) id = handle;
  if (!id) id = read_id_file(job_dir);
  if (!id) id = find_by_directory(job_dir);
  if (!id) return std::nullopt;
  std::lock_guard lock(mutex_);
  Watched w{job_dir, Clock::now(), {}};
  w.last.pending = true;
  watched_[*id] = w;
  return id;
}

bool SlurmExecutor::stop_orphan(const std::optional<std::string>& handle, const fs::path& job_dir) {
  auto id = reattach(handle, job_dir);
  if (!id) return false;
  cancel(*id);
  return true;
}

std::int64_t SlurmExecutor::queries() const {
  std::lock_guard lock(mutex_);
  return queries_;
}

}  // namespace rockcal::orch::slurm
