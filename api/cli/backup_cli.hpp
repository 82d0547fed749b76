// `rockcal backup` and `rockcal restore`: the live database copied with SQLite's backup API.
#pragma once

#include <string>

namespace rockcal::api {

// Copies the database `db` (the server may be running) to `out`; prints what it wrote.
int run_backup(const std::string& db, const std::string& out);

// Puts the backup `from` in place of `db`. Refuses while a server holds `data_dir`'s lock
// (default "<db>.d").
int run_restore(const std::string& from, const std::string& db, const std::string& data_dir);

}  // namespace rockcal::api
