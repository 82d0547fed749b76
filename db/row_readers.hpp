// Column lists and row readers shared by the store's writes (RETURNING) and reads. Internal to db/.
#pragma once

#include <string>

#include "db/records.hpp"
#include "db/sqlite.hpp"

namespace rockcal::db::detail {

inline constexpr const char* kJobColumns =
    "id, campaign_id, test, fr0, fs0, spec, hash, state, cached, attempts, error, progress, "
    "executor, handle, created_at, started_at, finished_at";

inline JobRow read_job(const Statement& st, int c = 0) {
  JobRow j;
  j.id = st.int64(c + 0);
  j.campaign_id = st.int64(c + 1);
  j.test = st.text(c + 2);
  j.fr0 = st.real(c + 3);
  j.fs0 = st.real(c + 4);
  j.spec = st.text(c + 5);
  j.hash = st.text(c + 6);
  j.state = st.text(c + 7);
  j.cached = st.int64(c + 8) != 0;
  j.attempts = static_cast<int>(st.int64(c + 9));
  j.error = st.opt_text(c + 10);
  j.progress = st.opt_real(c + 11);
  j.executor = st.opt_text(c + 12);
  j.handle = st.opt_text(c + 13);
  j.created_at = st.real(c + 14);
  j.started_at = st.opt_real(c + 15);
  j.finished_at = st.opt_real(c + 16);
  return j;
}
inline constexpr int kJobColumnCount = 17;

inline constexpr const char* kResultColumns =
    "hash, job_id, test, fr0, fs0, peak_load, strength, youngs_modulus, poisson_ratio, particles, "
    "wall_seconds, engine_version, result, curve, created_at, no_peak";

inline ResultRow read_result(const Statement& st, int c = 0) {
  ResultRow r;
  r.hash = st.text(c + 0);
  r.job_id = st.int64(c + 1);
  r.test = st.text(c + 2);
  r.fr0 = st.real(c + 3);
  r.fs0 = st.real(c + 4);
  r.peak_load = st.opt_real(c + 5);
  r.strength = st.opt_real(c + 6);
  r.youngs_modulus = st.opt_real(c + 7);
  r.poisson_ratio = st.opt_real(c + 8);
  r.particles = st.opt_int64(c + 9);
  r.wall_seconds = st.opt_real(c + 10);
  r.engine_version = st.text(c + 11);
  r.result = st.text(c + 12);
  r.curve = st.opt_text(c + 13);
  r.created_at = st.real(c + 14);
  r.no_peak = st.opt_text(c + 15);
  return r;
}

// "a, b" -> "j.a, j.b"
inline std::string prefixed(const std::string& columns, const std::string& prefix) {
  std::string out = prefix;
  for (char ch : columns) {
    out += ch;
    if (ch == ' ') out += prefix;
  }
  return out;
}

// A result column list with the curve replaced by NULL, for listings that never show it.
inline std::string without_curve(std::string columns) {
  auto end = columns.find("curve") + 5;
  auto start = columns.rfind(' ', end) + 1;  // include any "r." prefix
  return columns.replace(start, end - start, "NULL");
}

inline constexpr const char* kCampaignColumns =
    "id, kind, name, request, created_at, cancel_requested, driver_status, summary";

inline CampaignRow read_campaign(const Statement& st) {
  CampaignRow c;
  c.id = st.int64(0);
  c.kind = st.text(1);
  c.name = st.text(2);
  c.request = st.text(3);
  c.created_at = st.real(4);
  c.cancel_requested = st.int64(5) != 0;
  c.driver_status = st.opt_text(6);
  c.summary = st.opt_text(7);
  return c;
}

}  // namespace rockcal::db::detail
