// A SQLite VFS shim for storage fault injection (as SQLite's own test suite does): it wraps the
// default VFS, becomes the default for connections opened after install(), and while a fault is
// set makes every write to a database, journal or WAL file fail with that result code (e.g.
// SQLITE_FULL: "database or disk is full"). Reads are untouched.
#pragma once

namespace rockcal::test {

// Registers the shim as the default VFS (once per process).
void install_fault_vfs();
// SQLITE_OK clears the fault.
void set_write_fault(int sqlite_code);

// Sets a write fault for its lifetime.
struct WriteFault {
  explicit WriteFault(int sqlite_code) { set_write_fault(sqlite_code); }
  ~WriteFault() { clear(); }
  void clear();
};

}  // namespace rockcal::test
