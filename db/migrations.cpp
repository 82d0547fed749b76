#include "db/migrations.hpp"

namespace rockcal::db {

const std::vector<Migration>& migrations() {
  static const std::vector<Migration> all = {
      {1, R"sql(
CREATE TABLE campaigns (
  id INTEGER PRIMARY KEY AUTOINCREMENT,
  kind TEXT NOT NULL,
  name TEXT NOT NULL,
  request TEXT NOT NULL,              -- the request as submitted (validated)
  created_at REAL NOT NULL,
  cancel_requested INTEGER NOT NULL DEFAULT 0,
  driver_status TEXT,                 -- NULL for kinds without a driver thread; else running|done|failed
  summary TEXT                        -- JSON a driver reports (e.g. calibrated parameters)
);
CREATE TABLE jobs (
  id INTEGER PRIMARY KEY AUTOINCREMENT,
  campaign_id INTEGER NOT NULL REFERENCES campaigns(id) ON DELETE CASCADE,
  test TEXT NOT NULL,
  fr0 REAL NOT NULL,
  fs0 REAL NOT NULL,
  spec TEXT NOT NULL,                 -- canonical job spec, as written to job.json
  hash TEXT NOT NULL,                 -- identity: sha256 of spec (output removed) + engine version
  state TEXT NOT NULL CHECK (state IN ('queued', 'running', 'succeeded', 'failed', 'cancelled')),
  cached INTEGER NOT NULL DEFAULT 0,  -- 1: answered from an earlier result, never run
  attempts INTEGER NOT NULL DEFAULT 0,
  error TEXT,
  progress REAL,
  executor TEXT,                      -- which executor runs it, and its handle (local: the pgid)
  handle TEXT,
  created_at REAL NOT NULL,
  started_at REAL,
  finished_at REAL
);
CREATE INDEX jobs_by_state ON jobs (state, id);
CREATE INDEX jobs_by_campaign ON jobs (campaign_id, id);
CREATE INDEX jobs_by_hash ON jobs (hash);
CREATE TABLE results (
  hash TEXT PRIMARY KEY,              -- one result per identity, whatever campaigns asked for it
  job_id INTEGER NOT NULL REFERENCES jobs(id),
  test TEXT NOT NULL,
  fr0 REAL NOT NULL,
  fs0 REAL NOT NULL,
  peak_load REAL,
  strength REAL,
  youngs_modulus REAL,
  poisson_ratio REAL,
  particles INTEGER,
  wall_seconds REAL,
  engine_version TEXT NOT NULL,
  result TEXT NOT NULL,               -- result.json as the engine wrote it
  curve TEXT,                         -- curve.csv, kept so a plot survives the data directory
  created_at REAL NOT NULL
);
CREATE INDEX results_by_point ON results (test, fr0, fs0);
)sql"},
      // A run that ended without a peak ("peak_reached": false) is a failed job whose
      // result stays for inspection: no_peak says why, and the value columns are emptied so that
      // nothing takes its largest load for a peak. Stored runs are judged by the rule of new ones
      // (orch::no_peak_reason), except that engines before 0.2.0 also wrote peak_reached false for
      // the elastic test, which has no peak to reach.
      {2, R"sql(
ALTER TABLE results ADD COLUMN no_peak TEXT;
UPDATE results SET
  no_peak = COALESCE(NULLIF(json_extract(result, '$.no_peak_reason'), ''),
                     'the run stopped (' || COALESCE(json_extract(result, '$.stop_reason'), '?') ||
                     ') before a peak'),
  peak_load = NULL, strength = NULL, youngs_modulus = NULL, poisson_ratio = NULL
  WHERE test <> 'elastic' AND json_valid(result) AND json_extract(result, '$.peak_reached') = 0;
UPDATE jobs SET state = 'failed',
  error = 'no peak: ' || (SELECT no_peak FROM results r WHERE r.hash = jobs.hash)
  WHERE state = 'succeeded' AND hash IN (SELECT hash FROM results WHERE no_peak IS NOT NULL);
)sql"},
  };
  return all;
}

int migrate(Connection& conn) {
  conn.exec("CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)");
  int current = 0;
  {
    Transaction tx(conn);
    auto st = conn.prepare("SELECT COALESCE(MAX(version), 0) FROM schema_version");
    if (st.step()) current = static_cast<int>(st.int64(0));
    tx.commit();
  }
  for (const auto& m : migrations()) {
    if (m.version <= current) continue;
    Transaction tx(conn);
    // Re-check under the write lock: two processes may start together.
    auto st = conn.prepare("SELECT COALESCE(MAX(version), 0) FROM schema_version");
    st.step();
    if (st.int64(0) >= m.version) continue;
    conn.exec(m.sql);
    conn.prepare("INSERT INTO schema_version (version) VALUES (?)").bind_all(m.version).run();
    tx.commit();
    current = m.version;
  }
  return current;
}

}  // namespace rockcal::db
