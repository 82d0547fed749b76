// Load: 50 concurrent clients query and submit on loopback against the real server for
// ROCKCAL_LOAD_SECONDS (default 10 s in the default suite; the figure is 30 s: run with
// ROCKCAL_LOAD_SECONDS=30). No 5xx, no "database is locked", no request lost: a request dropped
// without an answer is resent once and must then succeed, and drops must stay below 1 in 1,000.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <iostream>
#include <random>
#include <thread>

#include "db/sqlite.hpp"
#include "support.hpp"

namespace rockcal::test {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

int load_seconds() {
  const char* env = std::getenv("ROCKCAL_LOAD_SECONDS");
  return env ? std::max(1, std::atoi(env)) : 10;
}

TEST(Load, FiftyConcurrentClientsGetNo5xxAndNoLockErrors) {
  TempDir dir;
  ServerProcess server(dir.path(),
                       {"--engine", engine_binary(), "--ranks-per-job", "0", "--workers", "2"});
  server.start();
  const int clients = 50;
  const auto duration = std::chrono::seconds(load_seconds());
  std::atomic<long> total{0}, posts{0}, ok{0}, client_errors{0}, server_errors{0}, transport{0};
  std::atomic<long> locked{0}, dropped{0};
  std::mutex first_error_mutex;
  std::string first_error, first_drop;
  auto deadline = std::chrono::steady_clock::now() + duration;

  auto client_loop = [&](int seed) {
    std::mt19937 rng(seed);
    auto c = server.client();
    c.set_keep_alive(true);
    long local_campaigns = 0;
    while (std::chrono::steady_clock::now() < deadline) {
      int pick = static_cast<int>(rng() % 10);
      if (pick == 0) {
        ++posts;
        ++local_campaigns;
      }
      // The request is built once, so a retry resends exactly the same thing.
      std::string path, body, what;
      if (pick == 0) {
        // A new point each time (fresh jobs), sometimes a repeat (cache).
        double fr0 = 20 + static_cast<double>(rng() % 2000) / 10.0;
        body = sweep_request({"uct"}, {fr0}, {64}).dump();
        path = "/api/v1/campaigns";
        what = "POST " + path;
      } else if (pick <= 3) {
        path = "/api/v1/campaigns/" + std::to_string(1 + rng() % (local_campaigns + 5));
      } else if (pick == 4) {
        path = "/api/v1/campaigns?limit=20";
      } else if (pick == 5) {
        path = "/api/v1/campaigns/" + std::to_string(1 + rng() % 20) + "/results";
      } else if (pick == 6) {
        path = "/api/v1/results?test=uct&fr0_min=30&fr0_max=120";
      } else if (pick == 7) {
        path = "/metrics";
      } else if (pick == 8) {
        path = "/api/v1/jobs/" + std::to_string(1 + rng() % 50);
      } else {
        path = "/healthz";
      }
      if (what.empty()) what = "GET " + path;
      auto send = [&] { return pick == 0 ? c.Post(path, body, "application/json") : c.Get(path); };
      httplib::Result r = send();
      if (!r) {
        // Dropped without an answer (seen about once in 8,000 requests in fresh-clone CI runs,
        // never reproduced locally; cause unknown). Resent once, as a client would; a POST the
        // server had stored would show up below as one campaign too many.
        ++dropped;
        {
          std::lock_guard lock(first_error_mutex);
          if (first_drop.empty()) first_drop = httplib::to_string(r.error()) + " on " + what;
        }
        r = send();
      }
      ++total;
      if (!r) {
        ++transport;
        std::lock_guard lock(first_error_mutex);
        if (first_error.empty()) {
          first_error = "transport, twice: " + httplib::to_string(r.error()) + " on " + what;
        }
        continue;
      }
      if (r->body.find("locked") != std::string::npos) ++locked;
      if (r->status >= 500) {
        ++server_errors;
        std::lock_guard lock(first_error_mutex);
        if (first_error.empty()) first_error = std::to_string(r->status) + " " + r->body;
      } else if (r->status >= 400) {
        ++client_errors;  // e.g. 404 for a campaign id not created yet: expected
      } else {
        ++ok;
      }
    }
  };
  auto t0 = std::chrono::steady_clock::now();
  std::vector<std::thread> threads;
  for (int i = 0; i < clients; ++i) threads.emplace_back(client_loop, i + 1);
  for (auto& t : threads) t.join();
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  double rate = static_cast<double>(total) / seconds;
  std::cout << "load: " << clients << " clients, " << seconds << " s, " << total << " requests ("
            << rate << " req/s), " << posts << " submissions, " << ok << " 2xx, " << client_errors
            << " 4xx, " << server_errors << " 5xx, " << transport << " transport errors, "
            << dropped << " dropped and resent"
            << (first_drop.empty() ? "" : " (first: " + first_drop + ")") << "\n";
  RecordProperty("requests_per_second", std::to_string(rate));
  EXPECT_EQ(server_errors.load(), 0) << first_error;
  EXPECT_EQ(transport.load(), 0) << first_error;
  EXPECT_LE(dropped.load(), total.load() / 1000) << first_drop;
  EXPECT_EQ(locked.load(), 0);
  EXPECT_GT(posts.load(), 0);
  EXPECT_GT(ok.load(), total.load() / 2);
  EXPECT_EQ(server.stderr_text().find("locked"), std::string::npos) << server.stderr_text();
  EXPECT_EQ(server.terminate(), 0);
  db::Connection conn(server.db().string());
  auto check = conn.prepare("PRAGMA integrity_check");
  ASSERT_TRUE(check.step());
  EXPECT_EQ(check.text(0), "ok");
  auto campaigns = conn.prepare("SELECT COUNT(*) FROM campaigns");
  ASSERT_TRUE(campaigns.step());
  EXPECT_EQ(campaigns.int64(0), posts.load()) << "every accepted submission stored once";
}

}  // namespace
}  // namespace rockcal::test
