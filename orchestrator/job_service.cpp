#include "orchestrator/job_service.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <iostream>

#include "engine/json_input.hpp"
#include "orchestrator/campaign_status.hpp"
#include "orchestrator/job_files.hpp"
#include "orchestrator/job_identity.hpp"
#include "orchestrator/request_error.hpp"

namespace rockcal::orch {
namespace fs = std::filesystem;
using nlohmann::json;

JobService::JobService(ServiceConfig config, std::unique_ptr<Executor> executor)
    : config_(std::move(config)), executor_(std::move(executor)) {
  if (config_.data_dir.empty()) config_.data_dir = config_.db_path.string() + ".d";
  config_.data_dir = fs::absolute(config_.data_dir);
  if (config_.jobs_dir.empty()) config_.jobs_dir = config_.data_dir / "jobs";
  config_.jobs_dir = fs::absolute(config_.jobs_dir);
  fs::create_directories(config_.data_dir);
  fs::create_directories(config_.jobs_dir);
  // One server per database: a second one would re-queue and kill the first one's jobs.
  auto lock_path = config_.data_dir / "server.lock";
  lock_fd_ = open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0 || flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    if (lock_fd_ >= 0) close(lock_fd_);
    throw std::runtime_error("another rockcal server is using " + config_.data_dir.string());
  }
  store_ = std::make_unique<db::Store>(config_.db_path.string(), config_.busy_timeout_ms);
  auto reattached = recover();
  PoolConfig pool;
  pool.workers = config_.workers;
  pool.max_attempts = config_.max_attempts;
  pool.job_timeout = config_.job_timeout;
  pool.jobs_dir = config_.jobs_dir;
  pool.poll_interval = config_.poll_interval;
  pool.storage_retry = config_.storage_retry;
  pool_ = std::make_unique<WorkerPool>(*store_, *executor_, pool,
                                       [this](std::int64_t id) { job_done(id); });
  for (const auto& [job, handle] : reattached) pool_->resume(job, handle);
}

JobService::~JobService() {
  stop();
  if (lock_fd_ >= 0) close(lock_fd_);
}

std::vector<std::pair<db::JobRow, std::string>> JobService::recover() {
  // Every job an executor owns belongs to a server that died or stopped: nothing else runs jobs
  // of this database (the lock above). A scheduler's job goes on and is watched again (never
  // submitted twice); anything else is stopped and run again.
  std::vector<std::pair<db::JobRow, std::string>> reattached;
  for (const auto& job : store_->owned_jobs()) {
    fs::path dir = job_dir(config_.jobs_dir, job.id);
    if (job.executor == executor_->name()) {
      if (executor_->jobs_outlive_server()) {
        // Throws when the scheduler cannot be asked: better no server than a job run twice.
        if (auto handle = executor_->reattach(job.handle, dir)) {
          if (job.handle != handle) store_->set_handle(job.id, *handle);
          reattached.emplace_back(job, *handle);
          ++reattached_jobs_;
          continue;
        }
      }
      try {
        if (executor_->stop_orphan(job.handle, dir)) ++stopped_orphans_;
      } catch (const std::exception& e) {
        std::cerr << "rockcal: stopping orphan of job " << job.id << ": " << e.what() << "\n";
      }
    } else if (job.handle) {
      std::cerr << "rockcal: job " << job.id << " was left to executor "
                << job.executor.value_or("?") << " (handle " << *job.handle
                << "), which this server does not use; it is run again here\n";
    }
    store_->requeue(job.id, "re-queued after a server restart");
    ++recovered_jobs_;
  }
  return reattached;
}

void JobService::start() {
  if (started_) return;
  started_ = true;
  pool_->start();
  for (const auto& c : store_->campaigns(1 << 30, 0)) {
    if (c.driver_status != std::optional<std::string>("running")) continue;
    if (const auto* kind = kinds_.find(c.kind); kind && kind->driver) {
      start_driver(c.id, *kind, parse_json_input(c.request));
    }
  }
}

void JobService::stop() {
  {
    std::lock_guard lock(drivers_mutex_);
    for (auto& [id, t] : drivers_) t.request_stop();
  }
  done_cv_.notify_all();
  std::map<std::int64_t, std::jthread> drivers;
  {
    std::lock_guard lock(drivers_mutex_);
    drivers.swap(drivers_);
  }
  drivers.clear();  // joins
  if (pool_) pool_->stop();
  started_ = false;
}

CampaignPlan JobService::plan_campaign(const json& request, const CampaignKind** kind_out) const {
  if (!request.is_object()) throw RequestError("(body)", "must be a JSON object");
  auto it = request.find("kind");
  if (it == request.end()) throw RequestError("kind", "is required");
  if (!it->is_string()) throw RequestError("kind", "must be a string");
  const CampaignKind* kind = kinds_.find(it->get<std::string>());
  if (!kind) {
    std::string known;
    for (const auto& n : kinds_.names()) known += (known.empty() ? "" : ", ") + n;
    throw RequestError("kind",
                       "unknown kind '" + it->get<std::string>() + "' (known: " + known + ")");
  }
  if (kind_out) *kind_out = kind;
  return kind->plan(request, config_.limits);
}

std::int64_t JobService::create_campaign(const json& request) {
  const CampaignKind* kind = nullptr;
  CampaignPlan plan = plan_campaign(request, &kind);
  std::int64_t id = store_->create_campaign(kind->name, plan.name, request.dump(),
                                            static_cast<bool>(kind->driver), plan.jobs);
  pool_->wake();
  if (kind->driver && started_) start_driver(id, *kind, request);
  return id;
}

db::CancelOutcome JobService::cancel_campaign(std::int64_t campaign_id) {
  auto outcome = store_->cancel_campaign(campaign_id);
  if (outcome == db::CancelOutcome::cancelled) {
    std::lock_guard lock(drivers_mutex_);
    if (auto it = drivers_.find(campaign_id); it != drivers_.end()) it->second.request_stop();
  }
  job_done(0);  // wake waiters: their jobs may have been cancelled
  return outcome;
}

void JobService::start_driver(std::int64_t campaign_id, const CampaignKind& kind, json request) {
  std::lock_guard lock(drivers_mutex_);
  drivers_[campaign_id] = std::jthread([this, campaign_id, &kind, request](std::stop_token stop) {
    DriverContext ctx{*this, campaign_id, request, stop};
    std::string status, summary;
    try {
      summary = kind.driver(ctx).dump();
      status = "done";
    } catch (const std::exception& e) {
      summary = json{{"error", e.what()}}.dump();
      status = "failed";
    }
    try {
      // Stopped for a shutdown: left running, so the next start resumes it. Cancelled: the
      // cancellation has recorded its end.
      if (stop.stop_requested() || store_->campaign(campaign_id)->cancel_requested) return;
      // The end waits out a storage fault; if the service stops first, the next start runs the
      // driver again (its jobs answered from the store).
      write_with_retry(
          *store_, [&] { store_->set_driver_status(campaign_id, status, summary); },
          config_.storage_retry, stop);
    } catch (const std::exception& e) {
      std::cerr << "rockcal: campaign " << campaign_id << ": its end was not stored: " << e.what()
                << "\n";
    }
  });
}

void JobService::job_done(std::int64_t) {
  {
    std::lock_guard lock(done_mutex_);
    ++done_generation_;
  }
  done_cv_.notify_all();
}

std::int64_t JobService::submit_job(std::int64_t campaign_id, const json& job_spec,
                                    std::stop_token stop) {
  db::NewJob job = make_job(job_spec);
  std::int64_t id = 0;
  if (!write_with_retry(
          *store_, [&] { id = store_->add_job(campaign_id, job); }, config_.driver_storage_retry,
          stop)) {
    return 0;
  }
  pool_->wake();
  return id;
}

JobOutcome JobService::wait_job(std::int64_t job_id, std::stop_token stop) {
  while (true) {
    std::uint64_t generation;
    {
      std::lock_guard lock(done_mutex_);
      generation = done_generation_;
    }
    auto job = store_->job(job_id);
    if (!job) throw std::invalid_argument("no job " + std::to_string(job_id));
    if (is_terminal_job_state(job->state) || stop.stop_requested()) {
      JobOutcome out{job_id, job->state, job->cached, std::nullopt, job->error};
      if (job->state == db::kSucceeded) out.result = store_->result(job->hash);
      return out;
    }
    std::unique_lock lock(done_mutex_);
    // The timeout is a safety net only; job_done() wakes us when any job ends.
    done_cv_.wait_for(lock, stop, std::chrono::seconds(2),
                      [&] { return done_generation_ != generation; });
  }
}

void JobService::set_progress(std::int64_t campaign_id, const json& progress,
                              std::stop_token stop) {
  write_with_retry(
      *store_, [&] { store_->set_driver_status(campaign_id, "running", progress.dump()); },
      config_.driver_storage_retry, stop);
}

}  // namespace rockcal::orch
