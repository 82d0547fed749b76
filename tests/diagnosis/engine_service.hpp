// Test support: the real service (SQLite store, local executor running rockcal-dem without
// mpirun) for tests that make twins or diagnoses on the engine, and a wait for a driver campaign.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <thread>

#include <nlohmann/json.hpp>

#include "orchestrator/all_kinds.hpp"
#include "orchestrator/job_service.hpp"
#include "orchestrator/local_executor.hpp"

namespace rockcal::diagnosis::test {

// Two workers, store at `db`, every campaign kind; start() it.
inline std::unique_ptr<orch::JobService> engine_service(const std::filesystem::path& db,
                                                        const std::string& engine) {
  orch::ServiceConfig cfg;
  cfg.db_path = db;
  cfg.workers = 2;
  orch::LocalExecutorConfig exec;
  exec.engine = engine;
  exec.ranks = 0;
  auto service =
      std::make_unique<orch::JobService>(cfg, std::make_unique<orch::LocalExecutor>(exec));
  orch::add_all_kinds(service->kinds());
  return service;
}

// The campaign's summary once its driver is done; a failure (or a driver still running after
// `timeout`) fails the test and returns null.
inline nlohmann::json run_to_summary(orch::JobService& service, const nlohmann::json& request,
                                     std::chrono::seconds timeout) {
  const std::int64_t id = service.create_campaign(request);
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < end) {
    const auto c = service.store().campaign(id);
    if (c->driver_status == "done" || c->driver_status == "failed") {
      EXPECT_EQ(*c->driver_status, "done") << c->summary.value_or("");
      return nlohmann::json::parse(*c->summary);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ADD_FAILURE() << "campaign " << id << " did not finish in " << timeout.count() << " s";
  return nullptr;
}

}  // namespace rockcal::diagnosis::test
