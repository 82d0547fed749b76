#include "api/cli/backup_cli.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "db/backup.hpp"

namespace rockcal::api {
namespace fs = std::filesystem;

int run_backup(const std::string& db, const std::string& out) {
  auto t0 = std::chrono::steady_clock::now();
  auto report = db::backup_database(db, out);
  double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "rockcal: backed up " << db << " to " << out << " (" << report.pages << " pages in "
            << s << " s; integrity_check " << report.integrity << ")\n";
  return 0;
}

int run_restore(const std::string& from, const std::string& db, const std::string& data_dir) {
  // The server's lock (orchestrator/job_service.cpp): restoring under a running server would
  // pull the store from under its workers.
  fs::path lock_path = fs::path(data_dir.empty() ? db + ".d" : data_dir) / "server.lock";
  int fd = open(lock_path.c_str(), O_RDWR | O_CLOEXEC);
  if (fd >= 0 && flock(fd, LOCK_EX | LOCK_NB) != 0) {
    close(fd);
    throw std::runtime_error("a rockcal server is running on " + db + " (" + lock_path.string() +
                             " is locked); stop it before restoring");
  }
  auto report = db::restore_database(from, db);
  if (fd >= 0) close(fd);
  std::cout << "rockcal: restored " << db << " from " << from << " (" << report.pages
            << " pages; integrity_check " << report.integrity << ")\n";
  return 0;
}

}  // namespace rockcal::api
