// Storage faults: what SQLite reports when the database cannot take a write for a reason outside
// the program (another writer holds the lock, the disk is full, an I/O error), as against a bug
// (a constraint, a malformed statement). The store remembers the fault its writes last met until
// one succeeds again, and counts them by kind, for /healthz, /metrics and the HTTP status.
#pragma once

#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>

namespace rockcal::db {

// "busy" (SQLITE_BUSY, SQLITE_LOCKED), "full" (SQLITE_FULL), "io" (SQLITE_IOERR, SQLITE_CANTOPEN,
// SQLITE_READONLY, SQLITE_PROTOCOL), or "" for any other code: not a storage fault.
std::string storage_fault_kind(int sqlite_code);

struct StorageFault {
  std::string kind;     // storage_fault_kind()
  std::string message;  // SQLite's, e.g. "database or disk is full"
  double since = 0;     // when the fault was first met (seconds since the epoch)
};

// Thread-safe.
class StorageHealth {
 public:
  // A write failed with `kind` (not empty).
  void failed(const std::string& kind, const std::string& message);
  // A write succeeded: no fault is in force.
  void succeeded();
  std::optional<StorageFault> fault() const;
  std::map<std::string, std::int64_t> counts() const;

 private:
  mutable std::mutex mutex_;
  std::optional<StorageFault> fault_;
  std::map<std::string, std::int64_t> counts_;
};

}  // namespace rockcal::db
