// The SQL of the job queries that take an optional campaign. Each names the campaign in its WHERE
// clause only when one is given ("campaign_id = ?1", else "?1 IS NULL", bound to NULL): the form
// "(?1 IS NULL OR campaign_id = ?1)" would serve both with one text, but SQLite cannot use the
// jobs_by_campaign index for it and scans the whole jobs table for every campaign.
#pragma once

#include <string>

namespace rockcal::db {

// state, COUNT(*), SUM(cached), one row per state.
std::string job_counts_sql(bool one_campaign);
// The running jobs' columns (kJobColumns), by id.
std::string running_jobs_sql(bool one_campaign);
// COUNT(*) and the summed run time of the jobs that ran (not cached) and succeeded.
std::string job_durations_sql(bool one_campaign);

}  // namespace rockcal::db
