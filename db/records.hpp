// Plain rows of the store, as the orchestrator and the API see them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace rockcal::db {

// Job states, in the order a job passes through them.
inline constexpr const char* kQueued = "queued";
inline constexpr const char* kRunning = "running";
inline constexpr const char* kSucceeded = "succeeded";
inline constexpr const char* kFailed = "failed";
inline constexpr const char* kCancelled = "cancelled";

struct NewJob {
  std::string test;  // "uct" | "btt" | "elastic"
  double fr0 = 0;
  double fs0 = 0;
  std::string spec;  // canonical spec JSON
  std::string hash;  // identity hash
};

struct CampaignRow {
  std::int64_t id = 0;
  std::string kind;
  std::string name;
  std::string request;
  double created_at = 0;
  bool cancel_requested = false;
  std::optional<std::string> driver_status;
  std::optional<std::string> summary;
};

struct JobRow {
  std::int64_t id = 0;
  std::int64_t campaign_id = 0;
  std::string test;
  double fr0 = 0;
  double fs0 = 0;
  std::string spec;
  std::string hash;
  std::string state;
  bool cached = false;
  int attempts = 0;
  std::optional<std::string> error;
  std::optional<double> progress;
  std::optional<std::string> executor;
  std::optional<std::string> handle;
  double created_at = 0;
  std::optional<double> started_at;
  std::optional<double> finished_at;
};

struct ResultRow {
  std::string hash;
  std::int64_t job_id = 0;  // the job that computed it
  std::string test;
  double fr0 = 0;
  double fs0 = 0;
  std::optional<double> peak_load;
  std::optional<double> strength;
  std::optional<double> youngs_modulus;
  std::optional<double> poisson_ratio;
  std::optional<std::int64_t> particles;
  std::optional<double> wall_seconds;
  std::string engine_version;
  std::string result;  // result.json text
  std::optional<std::string> curve;
  double created_at = 0;
  // Set when the run ended without a peak (result.json "peak_reached": false): why. Its job is
  // failed, and peak_load, strength, youngs_modulus and poisson_ratio are empty; the result JSON
  // and the curve stay for inspection.
  std::optional<std::string> no_peak;
};

// A job with its result, if it has one (one row of a campaign's results table).
struct JobResultRow {
  JobRow job;
  std::optional<ResultRow> result;
};

struct StateCounts {
  std::int64_t queued = 0, running = 0, succeeded = 0, failed = 0, cancelled = 0;
  std::int64_t cached = 0;  // succeeded jobs answered from the store
  std::int64_t total() const { return queued + running + succeeded + failed + cancelled; }
  std::int64_t ended() const { return succeeded + failed + cancelled; }
};

// Unfinished jobs of one executor ("" for jobs no executor has taken yet).
struct ExecutorCounts {
  std::string executor;
  std::int64_t waiting = 0;  // queued, waiting for a worker
  std::int64_t pending = 0;  // queued in the executor's own scheduler (e.g. PENDING in Slurm)
  std::int64_t running = 0;
};

struct ResultFilter {
  std::optional<std::string> test;
  std::optional<double> fr0_min, fr0_max, fs0_min, fs0_max;
  std::int64_t limit = 1000;
  std::int64_t offset = 0;
};

// Durations of jobs that actually ran and succeeded, for /metrics and ETAs.
struct DurationStats {
  std::int64_t count = 0;
  double sum_seconds = 0;
};

}  // namespace rockcal::db
