// The store's reads. Plain SELECTs on a pooled connection; WAL lets them run beside a writer.
#include <string>

#include "db/job_queries.hpp"
#include "db/row_readers.hpp"
#include "db/store.hpp"

namespace rockcal::db {

using namespace detail;

namespace {

std::string campaign_scope(bool one_campaign) {
  return one_campaign ? "campaign_id = ?1" : "?1 IS NULL";
}

}  // namespace

std::string job_counts_sql(bool one_campaign) {
  return "SELECT state, COUNT(*), SUM(cached) FROM jobs WHERE " + campaign_scope(one_campaign) +
         " GROUP BY state";
}

std::string running_jobs_sql(bool one_campaign) {
  return std::string("SELECT ") + kJobColumns + " FROM jobs WHERE state = 'running' AND " +
         campaign_scope(one_campaign) + " ORDER BY id";
}

std::string job_durations_sql(bool one_campaign) {
  return "SELECT COUNT(*), COALESCE(SUM(finished_at - started_at), 0) FROM jobs "
         "WHERE state = 'succeeded' AND cached = 0 AND started_at IS NOT NULL AND " +
         campaign_scope(one_campaign);
}

std::optional<CampaignRow> Store::campaign(std::int64_t id) {
  auto conn = lease();
  auto st =
      conn->prepare(std::string("SELECT ") + kCampaignColumns + " FROM campaigns WHERE id = ?");
  st.bind_all(id);
  if (!st.step()) return std::nullopt;
  return read_campaign(st);
}

std::vector<CampaignRow> Store::campaigns(std::int64_t limit, std::int64_t offset) {
  auto conn = lease();
  auto st = conn->prepare(std::string("SELECT ") + kCampaignColumns +
                          " FROM campaigns ORDER BY id DESC LIMIT ? OFFSET ?");
  st.bind_all(limit, offset);
  std::vector<CampaignRow> out;
  while (st.step()) out.push_back(read_campaign(st));
  return out;
}

std::int64_t Store::campaign_count() {
  auto conn = lease();
  auto st = conn->prepare("SELECT COUNT(*) FROM campaigns");
  st.step();
  return st.int64(0);
}

StateCounts Store::counts(std::optional<std::int64_t> campaign_id) {
  auto conn = lease();
  auto st = conn->prepare(job_counts_sql(campaign_id.has_value()));
  st.bind_all(campaign_id);
  StateCounts c;
  while (st.step()) {
    std::string state = st.text(0);
    std::int64_t n = st.int64(1);
    if (state == kQueued) c.queued = n;
    if (state == kRunning) c.running = n;
    if (state == kSucceeded) c.succeeded = n, c.cached = st.int64(2);
    if (state == kFailed) c.failed = n;
    if (state == kCancelled) c.cancelled = n;
  }
  return c;
}

std::vector<JobRow> Store::running_jobs(std::optional<std::int64_t> campaign_id) {
  auto conn = lease();
  auto st = conn->prepare(running_jobs_sql(campaign_id.has_value()));
  st.bind_all(campaign_id);
  std::vector<JobRow> out;
  while (st.step()) out.push_back(read_job(st));
  return out;
}

std::vector<JobRow> Store::owned_jobs() {
  auto conn = lease();
  auto st = conn->prepare(std::string("SELECT ") + kJobColumns +
                          " FROM jobs WHERE state = 'running' OR (state = 'queued' AND handle IS "
                          "NOT NULL) ORDER BY id");
  std::vector<JobRow> out;
  while (st.step()) out.push_back(read_job(st));
  return out;
}

std::vector<ExecutorCounts> Store::executor_counts() {
  auto conn = lease();
  // A job waiting for a worker keeps the executor of its last attempt; it is nobody's until
  // claimed, so it is counted under "".
  auto st = conn->prepare(
      "SELECT CASE WHEN state = 'queued' AND handle IS NULL THEN '' ELSE COALESCE(executor, '') "
      "END AS e, SUM(state = 'queued' AND handle IS NULL), SUM(state = 'queued' AND handle IS NOT "
      "NULL), SUM(state = 'running') FROM jobs WHERE state IN ('queued', 'running') GROUP BY e "
      "ORDER BY e");
  std::vector<ExecutorCounts> out;
  while (st.step()) out.push_back({st.text(0), st.int64(1), st.int64(2), st.int64(3)});
  return out;
}

std::optional<JobRow> Store::job(std::int64_t id) {
  auto conn = lease();
  auto st = conn->prepare(std::string("SELECT ") + kJobColumns + " FROM jobs WHERE id = ?");
  st.bind_all(id);
  if (!st.step()) return std::nullopt;
  return read_job(st);
}

std::string Store::job_state(std::int64_t id) {
  auto conn = lease();
  auto st = conn->prepare("SELECT state FROM jobs WHERE id = ?");
  st.bind_all(id);
  return st.step() ? st.text(0) : std::string();
}

std::vector<JobResultRow> Store::campaign_results(std::int64_t campaign_id, std::int64_t limit,
                                                  std::int64_t offset) {
  auto conn = lease();
  // The curve is left out (NULL): a results table never needs it and it is the bulk of a row.
  std::string sql = "SELECT " + prefixed(kJobColumns, "j.") + ", " +
                    without_curve(prefixed(kResultColumns, "r.")) +
                    " FROM jobs j LEFT JOIN results r ON r.hash = j.hash AND j.state = 'succeeded' "
                    "WHERE j.campaign_id = ? ORDER BY j.id LIMIT ? OFFSET ?";
  auto st = conn->prepare(sql);
  st.bind_all(campaign_id, limit, offset);
  std::vector<JobResultRow> out;
  while (st.step()) {
    JobResultRow row{read_job(st), std::nullopt};
    if (!st.is_null(kJobColumnCount)) row.result = read_result(st, kJobColumnCount);
    out.push_back(std::move(row));
  }
  return out;
}

std::optional<ResultRow> Store::result(const std::string& hash) {
  auto conn = lease();
  auto st = conn->prepare(std::string("SELECT ") + kResultColumns + " FROM results WHERE hash = ?");
  st.bind_all(hash);
  if (!st.step()) return std::nullopt;
  return read_result(st);
}

std::vector<ResultRow> Store::results(const ResultFilter& f) {
  auto conn = lease();
  auto st = conn->prepare("SELECT " + without_curve(kResultColumns) +
                          " FROM results WHERE (?1 IS NULL OR test = ?1) "
                          "AND (?2 IS NULL OR fr0 >= ?2) AND (?3 IS NULL OR fr0 <= ?3) "
                          "AND (?4 IS NULL OR fs0 >= ?4) AND (?5 IS NULL OR fs0 <= ?5) "
                          "ORDER BY test, fr0, fs0 LIMIT ?6 OFFSET ?7");
  st.bind_all(f.test, f.fr0_min, f.fr0_max, f.fs0_min, f.fs0_max, f.limit, f.offset);
  std::vector<ResultRow> out;
  while (st.step()) out.push_back(read_result(st));
  return out;
}

DurationStats Store::durations(std::optional<std::int64_t> campaign_id) {
  auto conn = lease();
  auto st = conn->prepare(job_durations_sql(campaign_id.has_value()));
  st.bind_all(campaign_id);
  st.step();
  return {st.int64(0), st.real(1)};
}

std::vector<std::int64_t> Store::duration_buckets(const std::vector<double>& upper_bounds) {
  auto conn = lease();
  auto st = conn->prepare(
      "SELECT COUNT(*) FROM jobs WHERE state = 'succeeded' AND cached = 0 "
      "AND started_at IS NOT NULL AND finished_at - started_at <= ?");
  std::vector<std::int64_t> out;
  for (double bound : upper_bounds) {
    st.bind_all(bound);
    st.step();
    out.push_back(st.int64(0));
    st.reset();
  }
  return out;
}

}  // namespace rockcal::db
