// The orchestrator's front: creates and cancels campaigns, runs the worker pool and campaign
// drivers, recovers after a crash, and lets a driver submit a job and wait for its result.
#pragma once

#include <condition_variable>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <stop_token>
#include <thread>

#include <nlohmann/json.hpp>

#include "db/store.hpp"
#include "orchestrator/campaign_kinds.hpp"
#include "orchestrator/executor.hpp"
#include "orchestrator/storage_retry.hpp"
#include "orchestrator/worker_pool.hpp"

namespace rockcal::orch {

struct ServiceConfig {
  std::filesystem::path db_path = "rockcal.db";
  std::filesystem::path data_dir;  // empty: "<db_path>.d"
  std::filesystem::path jobs_dir;  // a directory per job; empty: "<data_dir>/jobs"
  int workers = 1;
  int max_attempts = 3;
  std::chrono::milliseconds job_timeout{std::chrono::hours(6)};
  std::chrono::milliseconds poll_interval{100};  // the longest wait between looks at a job
  int busy_timeout_ms = 10000;  // a store write waits this long for another writer's lock
  // A store write that meets a storage fault (a full disk, a lock held past busy_timeout_ms) waits
  // and tries again. A worker recording a job's outcome, and a driver recording its campaign's end,
  // try until the write lands or the service stops; a driver's other writes (a job it submits, its
  // progress) give up after driver_storage_retry.give_up_after, which fails the campaign.
  StorageRetry storage_retry;
  StorageRetry driver_storage_retry{.give_up_after = std::chrono::minutes(10)};
  Limits limits;
};

// How a submitted job ended.
struct JobOutcome {
  std::int64_t job_id = 0;
  std::string state;                    // succeeded | failed | cancelled (or running if stopped)
  bool cached = false;                  // answered from the store without running
  std::optional<db::ResultRow> result;  // when succeeded: peak_load, strength, ..., result JSON
  std::optional<std::string> error;     // when failed: the reason and the last log lines
};

class JobService {
 public:
  // Opens the store (migrating it), locks the data directory against a second server, and
  // recovers jobs a crashed server left running (their orphaned processes are stopped).
  JobService(ServiceConfig config, std::unique_ptr<Executor> executor);
  ~JobService();

  // Starts the workers and resumes the drivers of unfinished driver campaigns.
  void start();
  // Stops drivers and workers; running jobs are stopped and re-queued for the next start.
  void stop();

  // Kinds known to create_campaign (orchestrator/all_kinds.hpp adds them all). Before start().
  KindRegistry& kinds() { return kinds_; }

  // Validates the whole request (throws RequestError naming the field) and stores the campaign
  // and its jobs in one transaction. Returns the campaign id.
  std::int64_t create_campaign(const nlohmann::json& request);
  // The validation part of create_campaign: the kind and its plan, nothing stored. Throws
  // RequestError naming the field.
  CampaignPlan plan_campaign(const nlohmann::json& request,
                             const CampaignKind** kind = nullptr) const;

  db::CancelOutcome cancel_campaign(std::int64_t campaign_id);

  // ---- for campaign drivers (e.g. calibration) ----
  // Adds a job for `job_spec` (a full job spec, "test" included) to the campaign and returns its
  // id. A spec whose result is already stored is answered at once (cached). Throws RequestError
  // for an invalid spec. A storage fault is waited out (driver_storage_retry); returns 0 when
  // `stop` is requested before the job could be stored.
  std::int64_t submit_job(std::int64_t campaign_id, const nlohmann::json& job_spec,
                          std::stop_token stop = {});
  // Blocks until the job ends, or `stop` is requested (then state is whatever it is now).
  JobOutcome wait_job(std::int64_t job_id, std::stop_token stop = {});
  // Stores a running campaign's summary (its progress so far), waiting out a storage fault
  // (driver_storage_retry); gives up quietly when `stop` is requested first.
  void set_progress(std::int64_t campaign_id, const nlohmann::json& progress, std::stop_token stop);

  db::Store& store() { return *store_; }
  const ServiceConfig& config() const { return config_; }
  const std::filesystem::path& data_dir() const { return config_.data_dir; }
  const std::filesystem::path& jobs_dir() const { return config_.jobs_dir; }
  const Executor& executor() const { return *executor_; }
  const FailureCounts& failures() const { return pool_->failures(); }
  // Jobs re-queued at start-up after a crash, and how many orphaned process groups were stopped.
  std::int64_t recovered_jobs() const { return recovered_jobs_; }
  std::int64_t stopped_orphans() const { return stopped_orphans_; }
  // Jobs a previous server left in the executor's scheduler that this one watches again.
  std::int64_t reattached_jobs() const { return reattached_jobs_; }

 private:
  // Returns the jobs re-attached (with their handles), for the pool to watch.
  std::vector<std::pair<db::JobRow, std::string>> recover();
  void start_driver(std::int64_t campaign_id, const CampaignKind& kind, nlohmann::json request);
  void job_done(std::int64_t job_id);

  ServiceConfig config_;
  std::unique_ptr<db::Store> store_;
  std::unique_ptr<Executor> executor_;
  std::unique_ptr<WorkerPool> pool_;
  KindRegistry kinds_;
  int lock_fd_ = -1;
  std::int64_t recovered_jobs_ = 0;
  std::int64_t stopped_orphans_ = 0;
  std::int64_t reattached_jobs_ = 0;

  std::mutex done_mutex_;
  std::condition_variable_any done_cv_;
  std::uint64_t done_generation_ = 0;

  std::mutex drivers_mutex_;
  std::map<std::int64_t, std::jthread> drivers_;
  bool started_ = false;
};

}  // namespace rockcal::orch
