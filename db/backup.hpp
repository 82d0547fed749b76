// Copies of a live database through SQLite's online backup API. A file copy of a database in WAL
// mode can miss commits still in the -wal file or tear a page being checkpointed; the backup API
// reads one consistent snapshot while the server goes on writing.
#pragma once

#include <cstdint>
#include <string>

namespace rockcal::db {

struct BackupReport {
  std::int64_t pages = 0;
  std::string integrity;  // PRAGMA integrity_check of the copy: "ok" when sound
};

// Writes a consistent copy of `source` (which may be in use) to `destination`, atomically
// (a temporary file renamed into place), and checks the copy. Throws on any failure, and when
// destination is the source itself.
BackupReport backup_database(const std::string& source, const std::string& destination);

// Replaces the database `target` by the copy `backup` (the server must be stopped), through the
// same API, so the target's own -wal and -shm files stay consistent. Throws on failure.
BackupReport restore_database(const std::string& backup, const std::string& target);

}  // namespace rockcal::db
