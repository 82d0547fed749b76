#include "db/storage_faults.hpp"

#include <sqlite3.h>

#include <exception>
#include <string>

#include "db/store.hpp"

namespace rockcal::db {

std::string storage_fault_kind(int sqlite_code) {
  switch (sqlite_code & 0xff) {  // the primary code of an extended one
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
      return "busy";
    case SQLITE_FULL:
      return "full";
    case SQLITE_IOERR:
    case SQLITE_CANTOPEN:
    case SQLITE_READONLY:
    case SQLITE_PROTOCOL:
      return "io";
    default:
      return "";
  }
}

void StorageHealth::failed(const std::string& kind, const std::string& message) {
  std::lock_guard lock(mutex_);
  ++counts_[kind];
  if (!fault_ || fault_->kind != kind) fault_ = StorageFault{kind, message, now_seconds()};
  fault_->message = message;
}

void StorageHealth::succeeded() {
  std::lock_guard lock(mutex_);
  fault_.reset();
}

std::optional<StorageFault> StorageHealth::fault() const {
  std::lock_guard lock(mutex_);
  return fault_;
}

std::map<std::string, std::int64_t> StorageHealth::counts() const {
  std::lock_guard lock(mutex_);
  return counts_;
}

std::string Store::note_failure(const SqliteError& e) {
  std::string kind = storage_fault_kind(e.code);
  if (!kind.empty()) health_.failed(kind, sqlite3_errstr(e.code));
  return kind;
}

std::optional<StorageFault> Store::probe_write() {
  auto conn = lease();
  sqlite3_busy_timeout(conn->raw(), 100);
  std::exception_ptr bug;
  try {
    // The header's user_version (rockcal keeps its schema version in a table) counts the probes:
    // a write that changes nothing would not reach the disk at all.
    Transaction tx(*conn);
    auto st = conn->prepare("PRAGMA user_version");
    st.step();
    const std::int64_t probes = st.int64(0);
    conn->exec("PRAGMA user_version = " + std::to_string((probes + 1) % 1000000));
    tx.commit();
    health_.succeeded();
  } catch (const SqliteError& e) {
    if (note_failure(e).empty()) bug = std::current_exception();
  }
  sqlite3_busy_timeout(conn->raw(), busy_timeout_ms_);
  if (bug) std::rethrow_exception(bug);
  return health_.fault();
}

}  // namespace rockcal::db
