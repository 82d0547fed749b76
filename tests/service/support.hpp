// Shared helpers for the service tests: temporary directories, polling, a `rockcal serve` child
// process on a free loopback port, and the tiny job template.
#pragma once

#include <httplib.h>
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rockcal::test {

// Paths baked in by CMake.
std::string rockcal_binary();
std::string engine_binary();  // the real rockcal-dem
std::string fake_engine();    // tests/service/fake-rockcal-dem.sh
std::string openapi_file();

class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Polls `condition` every 20 ms until it holds or `timeout` passes; returns whether it held.
bool poll_until(const std::function<bool()>& condition, std::chrono::milliseconds timeout);

// The tiny sample from the issue: a job runs in well under a second.
nlohmann::json tiny_job_template();
// A sweep request over `fr0` x `fs0` for `tests`, with the tiny template.
nlohmann::json sweep_request(const std::vector<std::string>& tests, const std::vector<double>& fr0,
                             const std::vector<double>& fs0);

// `rockcal serve` as a child process with its own database in `dir`.
class ServerProcess {
 public:
  // `extra` are further serve options (e.g. --engine, --workers).
  ServerProcess(const std::filesystem::path& dir, std::vector<std::string> extra);
  ~ServerProcess();
  void start();     // waits until it listens; throws if it does not within 30 s
  void kill9();     // SIGKILL and reap: a crash, not a shutdown
  int terminate();  // SIGTERM, wait, return the exit status
  bool running();
  int port() const { return port_; }
  std::string url() const { return "http://127.0.0.1:" + std::to_string(port_); }
  httplib::Client client() const;
  std::string stderr_text() const;
  std::filesystem::path db() const { return dir_ / "rockcal.db"; }
  std::filesystem::path data_dir() const { return dir_ / "rockcal.db.d"; }

 private:
  std::filesystem::path dir_;
  std::vector<std::string> extra_;
  pid_t pid_ = -1;
  int port_ = 0;
  int starts_ = 0;
};

// Live (non-zombie) processes whose command line mentions `needle` (e.g. a test's temp dir).
std::vector<pid_t> processes_mentioning(const std::string& needle);

// GET and parse JSON; fails the current test on a transport error.
nlohmann::json get_json(httplib::Client& client, const std::string& path, int expect_status = 200);

// Polls a campaign until its state is terminal; returns its last JSON.
nlohmann::json wait_campaign(httplib::Client& client, std::int64_t id,
                             std::chrono::seconds timeout);

}  // namespace rockcal::test
