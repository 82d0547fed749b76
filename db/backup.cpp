#include "db/backup.hpp"

#include <sqlite3.h>

#include <filesystem>
#include <stdexcept>

#include "db/sqlite.hpp"

namespace rockcal::db {
namespace fs = std::filesystem;

namespace {

struct Handle {
  sqlite3* db = nullptr;
  ~Handle() { sqlite3_close(db); }
};

void open(Handle& h, const std::string& path, int flags) {
  if (sqlite3_open_v2(path.c_str(), &h.db, flags, nullptr) != SQLITE_OK) {
    throw SqliteError(sqlite3_errcode(h.db),
                      "open " + path + ": " + (h.db ? sqlite3_errmsg(h.db) : "out of memory"));
  }
  sqlite3_busy_timeout(h.db, 10000);
}

// One step over all pages: in WAL mode the read transaction it holds is a snapshot that writers
// do not wait for, and a copy taken in one step never restarts when the source changes.
std::int64_t copy(sqlite3* from, sqlite3* to, const std::string& what) {
  sqlite3_backup* b = sqlite3_backup_init(to, "main", from, "main");
  if (!b) throw SqliteError(sqlite3_errcode(to), what + ": " + sqlite3_errmsg(to));
  int rc;
  do {
    rc = sqlite3_backup_step(b, -1);
    if (rc == SQLITE_BUSY || rc == SQLITE_LOCKED) sqlite3_sleep(50);
  } while (rc == SQLITE_OK || rc == SQLITE_BUSY || rc == SQLITE_LOCKED);
  std::int64_t pages = sqlite3_backup_pagecount(b);
  sqlite3_backup_finish(b);
  if (rc != SQLITE_DONE) throw SqliteError(rc, what + ": " + sqlite3_errstr(rc));
  return pages;
}

std::string integrity(const std::string& path) {
  Handle h;
  open(h, path, SQLITE_OPEN_READONLY);
  Statement st(h.db, "PRAGMA integrity_check");
  std::string out;
  while (st.step()) {
    if (!out.empty()) out += "; ";
    out += st.text(0);
  }
  return out;
}

}  // namespace

BackupReport backup_database(const std::string& source, const std::string& destination) {
  if (!fs::exists(source)) throw std::runtime_error("no database " + source);
  std::error_code ec;
  if (fs::exists(destination) && fs::equivalent(source, destination, ec)) {
    throw std::runtime_error("the backup must not overwrite the database itself");
  }
  const std::string tmp = destination + ".tmp";
  fs::remove(tmp);
  BackupReport report;
  {
    Handle from, to;
    open(from, source, SQLITE_OPEN_READONLY);
    open(to, tmp, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
    report.pages = copy(from.db, to.db, "backup of " + source);
    // The copy keeps the source's WAL flag; a backup is one self-contained file.
    char* err = nullptr;
    if (sqlite3_exec(to.db, "PRAGMA journal_mode=DELETE", nullptr, nullptr, &err) != SQLITE_OK) {
      std::string msg = err ? err : "?";
      sqlite3_free(err);
      throw std::runtime_error("backup of " + source + ": " + msg);
    }
  }
  report.integrity = integrity(tmp);
  if (report.integrity != "ok") {
    throw std::runtime_error("the copy of " + source +
                             " fails integrity_check: " + report.integrity);
  }
  fs::rename(tmp, destination);
  return report;
}

BackupReport restore_database(const std::string& backup, const std::string& target) {
  if (!fs::exists(backup)) throw std::runtime_error("no backup " + backup);
  if (integrity(backup) != "ok") throw std::runtime_error(backup + " fails integrity_check");
  BackupReport report;
  {
    Handle from, to;
    open(from, backup, SQLITE_OPEN_READONLY);
    open(to, target, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
    report.pages = copy(from.db, to.db, "restore of " + target);
  }
  report.integrity = integrity(target);
  if (report.integrity != "ok") {
    throw std::runtime_error(target +
                             " fails integrity_check after the restore: " + report.integrity);
  }
  return report;
}

}  // namespace rockcal::db
