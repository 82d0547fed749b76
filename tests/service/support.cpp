#include "support.hpp"

#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <gtest/gtest.h>

namespace rockcal::test {
namespace fs = std::filesystem;
using nlohmann::json;

std::string rockcal_binary() {
  return ROCKCAL_BIN;
}
std::string engine_binary() {
  return ROCKCAL_DEM;
}
std::string fake_engine() {
  return FAKE_ENGINE;
}
std::string openapi_file() {
  return OPENAPI_FILE;
}

TempDir::TempDir() {
  std::string tmpl = (fs::temp_directory_path() / "rockcal-test-XXXXXX").string();
  if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
  path_ = tmpl;
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

bool poll_until(const std::function<bool()>& condition, std::chrono::milliseconds timeout) {
  auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    if (condition()) return true;
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

json tiny_job_template() {
  // D = 8: a thinner disc (t = 3) loses its grains as floaters.
  return json::parse(R"({"sample": {"diameter": 8, "height": 12, "radius": 1},
    "material": {"density": 1, "kr": 8000, "nu": 0.2}, "bond": {"fr0": 64, "fs0": 64},
    "loading": {"platen_velocity": 0.05}})");
}

json sweep_request(const std::vector<std::string>& tests, const std::vector<double>& fr0,
                   const std::vector<double>& fs0) {
  return {{"kind", "sweep"},
          {"name", "test sweep"},
          {"tests", tests},
          {"job", tiny_job_template()},
          {"grid", {{"fr0", fr0}, {"fs0", fs0}}}};
}

ServerProcess::ServerProcess(const fs::path& dir, std::vector<std::string> extra)
    : dir_(dir), extra_(std::move(extra)) {}

ServerProcess::~ServerProcess() {
  if (pid_ > 0) kill9();
}

void ServerProcess::start() {
  fs::path port_file = dir_ / "port";
  fs::remove(port_file);
  std::vector<std::string> args = {rockcal_binary(), "serve",           "--db",
                                   db().string(),    "--listen",        "127.0.0.1:0",
                                   "--port-file",    port_file.string()};
  args.insert(args.end(), extra_.begin(), extra_.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::string out = (dir_ / "serve.out").string(), err = (dir_ / "serve.err").string();
  ++starts_;
  pid_ = fork();
  if (pid_ == 0) {
    int o = open(out.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    int e = open(err.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    dup2(o, 1);
    dup2(e, 2);
    execv(argv[0], argv.data());
    _exit(127);
  }
  bool up = poll_until(
      [&] {
        if (!running()) return true;
        return fs::exists(port_file);
      },
      std::chrono::seconds(30));
  if (!up || !running()) throw std::runtime_error("rockcal serve did not start: " + stderr_text());
  std::ifstream(port_file) >> port_;
}

bool ServerProcess::running() {
  if (pid_ <= 0) return false;
  int status = 0;
  if (waitpid(pid_, &status, WNOHANG) == pid_) {
    pid_ = -1;
    return false;
  }
  return true;
}

void ServerProcess::kill9() {
  if (pid_ <= 0) return;
  kill(pid_, SIGKILL);
  waitpid(pid_, nullptr, 0);
  pid_ = -1;
}

int ServerProcess::terminate() {
  if (pid_ <= 0) return -1;
  kill(pid_, SIGTERM);
  int status = 0;
  waitpid(pid_, &status, 0);
  pid_ = -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

httplib::Client ServerProcess::client() const {
  httplib::Client c("127.0.0.1", port_);
  c.set_connection_timeout(5, 0);
  c.set_read_timeout(30, 0);
  return c;
}

std::string ServerProcess::stderr_text() const {
  std::ifstream in(dir_ / "serve.err");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<pid_t> processes_mentioning(const std::string& needle) {
  std::vector<pid_t> out;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    try {  // a process may exit while we read it: libstdc++ then throws from underflow
      std::ifstream stat(entry.path() / "stat");
      std::string line;
      if (!std::getline(stat, line)) continue;
      auto close = line.rfind(')');
      if (close == std::string::npos || close + 2 >= line.size() || line[close + 2] == 'Z')
        continue;
      std::ifstream cmd(entry.path() / "cmdline", std::ios::binary);
      std::string cmdline((std::istreambuf_iterator<char>(cmd)), std::istreambuf_iterator<char>());
      if (cmdline.find(needle) != std::string::npos) out.push_back(std::stoi(name));
    } catch (const std::exception&) {
    }
  }
  return out;
}

json get_json(httplib::Client& client, const std::string& path, int expect_status) {
  auto r = client.Get(path);
  if (!r) {
    ADD_FAILURE() << "GET " << path << ": " << httplib::to_string(r.error());
    return nullptr;
  }
  EXPECT_EQ(r->status, expect_status) << "GET " << path << ": " << r->body;
  return json::parse(r->body, nullptr, false);
}

json wait_campaign(httplib::Client& client, std::int64_t id, std::chrono::seconds timeout) {
  json last;
  poll_until(
      [&] {
        last = get_json(client, "/api/v1/campaigns/" + std::to_string(id));
        if (!last.is_object()) return true;
        std::string s = last.value("state", "");
        return s == "succeeded" || s == "failed" || s == "cancelled";
      },
      timeout);
  return last;
}

}  // namespace rockcal::test
