// An in-process API server (real HTTP on a free loopback port) over a JobService that runs the
// fake engine: for API tests that need no real physics.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <thread>

#include "api/server/server.hpp"
#include "orchestrator/all_kinds.hpp"
#include "orchestrator/job_service.hpp"
#include "orchestrator/local_executor.hpp"
#include "support.hpp"

namespace rockcal::test {

struct ApiServerFixture : ::testing::Test {
  TempDir dir;
  std::unique_ptr<orch::JobService> service;
  std::unique_ptr<api::ApiServer> server;
  std::thread thread;
  int port = 0;

  // `configure` may change the server's settings (limits, allowed hosts) before it binds, and
  // `configure_service` the service's (e.g. the store's busy timeout).
  void start(std::optional<std::string> token = std::nullopt, std::size_t max_jobs = 100,
             const std::function<void(api::ServerConfig&)>& configure = {},
             const std::function<void(orch::ServiceConfig&)>& configure_service = {}) {
    orch::ServiceConfig cfg;
    cfg.db_path = dir.path() / "api.db";
    cfg.workers = 2;
    cfg.limits.max_jobs_per_campaign = max_jobs;
    if (configure_service) configure_service(cfg);
    orch::LocalExecutorConfig exec;
    exec.engine = fake_engine();
    exec.ranks = 0;
    service = std::make_unique<orch::JobService>(cfg, std::make_unique<orch::LocalExecutor>(exec));
    orch::add_all_kinds(service->kinds());
    api::ServerConfig sc;
    sc.port = 0;
    sc.token = token;
    sc.max_body_bytes = 64 * 1024;
    if (configure) configure(sc);
    server = std::make_unique<api::ApiServer>(*service, cfg.workers, sc);
    port = server->bind();
    service->start();
    thread = std::thread([this] { server->listen(); });
    ASSERT_TRUE(poll_until([&] { return server->is_running(); }, std::chrono::seconds(5)));
  }

  void TearDown() override {
    if (server) server->stop();
    if (thread.joinable()) thread.join();
    if (service) service->stop();
  }

  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port);
    c.set_read_timeout(30, 0);
    return c;
  }

  // Nothing of a rejected request may reach the store or the data directory.
  void expect_nothing_stored() {
    EXPECT_EQ(service->store().campaign_count(), 0);
    EXPECT_EQ(service->store().counts().total(), 0);
    EXPECT_TRUE(std::filesystem::is_empty(service->data_dir() / "jobs"));
  }
};

}  // namespace rockcal::test
