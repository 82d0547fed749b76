// Request framing against the real server, over raw sockets: a request whose end could be read two
// ways (a body on a GET, conflicting or malformed Content-Length, an unknown Transfer-Encoding) is
// refused before its body is read and its connection closed, so that bytes in a body are never
// served as a request of their own; methods no route takes get a 405 at once.
#include <gtest/gtest.h>

#include "api_server_fixture.hpp"
#include "raw_http.hpp"

namespace rockcal::test {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

struct RequestFraming : ApiServerFixture {
  std::string host() const { return "Host: 127.0.0.1:" + std::to_string(port) + "\r\n"; }

  // A sweep whose one job hangs (the fake engine's fr0 = 17): the campaign stays running, so a
  // cancel would show.
  std::int64_t running_campaign() {
    auto r = client().Post("/api/v1/campaigns", sweep_request({"uct"}, {17}, {1}).dump(),
                           "application/json");
    EXPECT_TRUE(r && r->status == 201);
    const auto id = json::parse(r->body)["id"].get<std::int64_t>();
    EXPECT_TRUE(poll_until([&] { return service->store().counts(id).running == 1; }, 10s));
    return id;
  }

  // Sends `request` on a connection of its own; returns all the server answers until it closes
  // the connection (or 3 s pass).
  std::string exchange(const std::string& request, bool* closed = nullptr) {
    RawConnection conn(port);
    conn.send(request);
    std::string answer = conn.read(3s);
    if (closed) *closed = !conn.send("x") || conn.closed_within(100ms);
    return answer;
  }
};

std::size_t responses_in(const std::string& answer) {
  std::size_t n = 0;
  for (auto at = answer.find("HTTP/1.1 "); at != std::string::npos;
       at = answer.find("HTTP/1.1 ", at + 1))
    ++n;
  return n;
}

TEST_F(RequestFraming, ARequestHiddenInTheBodyOfAGetIsNeverServed) {
  start();
  const std::int64_t id = running_campaign();
  const std::string hidden =
      "DELETE /api/v1/campaigns/" + std::to_string(id) + " HTTP/1.1\r\n" + host() + "\r\n";
  char chunk_size[16];
  std::snprintf(chunk_size, sizeof chunk_size, "%zx\r\n", hidden.size());
  // What `curl -X GET --data-binary "$hidden" -H 'Content-Type:' URL/healthz` sends, and the
  // same body chunked, and on a HEAD and a DELETE.
  for (const std::string& request : {
           "GET /healthz HTTP/1.1\r\n" + host() +
               "Content-Length: " + std::to_string(hidden.size()) + "\r\n\r\n" + hidden,
           "GET /healthz HTTP/1.1\r\n" + host() + "Transfer-Encoding: chunked\r\n\r\n" +
               chunk_size + hidden + "\r\n0\r\n\r\n",
           "HEAD /healthz HTTP/1.1\r\n" + host() +
               "Content-Length: " + std::to_string(hidden.size()) + "\r\n\r\n" + hidden,
           "DELETE /api/v1/campaigns/999 HTTP/1.1\r\n" + host() +
               "Content-Length: " + std::to_string(hidden.size()) + "\r\n\r\n" + hidden,
       }) {
    const std::string method = request.substr(0, request.find(' '));
    bool closed = false;
    const std::string answer = exchange(request, &closed);
    EXPECT_EQ(status_of(answer), 400) << answer;
    EXPECT_EQ(responses_in(answer), 1u) << answer;
    EXPECT_TRUE(closed) << request;
    if (method != "HEAD") {
      EXPECT_EQ(json::parse(body_of(answer), nullptr, false),
                json({{"error", method + " requests take no body"}, {"field", "(body)"}}))
          << answer;
    }
  }
  // The hidden DELETE did not run: the campaign is still there and running.
  auto c = client();
  const json campaign = get_json(c, "/api/v1/campaigns/" + std::to_string(id));
  EXPECT_EQ(campaign["state"], "running") << campaign.dump();
  EXPECT_FALSE(service->store().campaign(id)->cancel_requested);
  EXPECT_EQ(service->store().counts(id).running, 1);
}

TEST_F(RequestFraming, AmbiguousBodyLengthsAreRefusedAndStoreNothing) {
  start();
  const std::string body = sweep_request({"uct"}, {50}, {60}).dump();
  const std::string post =
      "POST /api/v1/campaigns HTTP/1.1\r\n" + host() + "Content-Type: application/json\r\n";
  struct Case {
    std::string headers;
    json error;
  };
  for (const auto& k : std::vector<Case>{
           {"Content-Length: 5\r\nContent-Length: " + std::to_string(body.size()) + "\r\n",
            {{"error",
              "conflicting Content-Length headers (5 and " + std::to_string(body.size()) + ")"},
             {"field", "Content-Length"}}},
           {"Content-Length: " + std::to_string(body.size()) + ", 5\r\n",
            {{"error", "Content-Length must be a decimal number of bytes (got '" +
                           std::to_string(body.size()) + ", 5')"},
             {"field", "Content-Length"}}},
           {"Content-Length: -1\r\n",
            {{"error", "Content-Length must be a decimal number of bytes (got '-1')"},
             {"field", "Content-Length"}}},
           {"Transfer-Encoding: gzip, chunked\r\n",
            {{"error", "Transfer-Encoding must be chunked alone (got 'gzip, chunked')"},
             {"field", "Transfer-Encoding"}}},
           {"Transfer-Encoding: chunked\r\nContent-Length: " + std::to_string(body.size()) + "\r\n",
            {{"error", "a request may not have both Content-Length and Transfer-Encoding"},
             {"field", "Transfer-Encoding"}}},
       }) {
    bool closed = false;
    const std::string answer = exchange(post + k.headers + "\r\n" + body, &closed);
    EXPECT_EQ(status_of(answer), 400) << k.headers << answer;
    EXPECT_EQ(json::parse(body_of(answer), nullptr, false), k.error) << k.headers;
    EXPECT_EQ(responses_in(answer), 1u) << answer;
    EXPECT_TRUE(closed) << k.headers;
  }
  expect_nothing_stored();
}

TEST_F(RequestFraming, MethodsNoRouteTakesGet405AtOnce) {
  start();
  const std::int64_t id = running_campaign();
  const std::string path = "/api/v1/campaigns/" + std::to_string(id);
  struct Case {
    std::string method;
    std::string path;
    std::string allow;
  };
  for (const auto& k : std::vector<Case>{{"PUT", path, "GET, HEAD, DELETE"},
                                         {"PATCH", path, "GET, HEAD, DELETE"},
                                         {"PUT", "/api/v1/campaigns", "POST, GET, HEAD"},
                                         {"OPTIONS", "/healthz", "GET, HEAD"},
                                         {"TRACE", "/", "GET, HEAD"}}) {
    // No Content-Length: what `curl -X PUT URL` sends. The server must not wait for a body.
    const auto t0 = Clock::now();
    const std::string answer =
        exchange(k.method + " " + k.path + " HTTP/1.1\r\n" + host() + "\r\n");
    EXPECT_LT(std::chrono::duration<double>(Clock::now() - t0).count(), 1.0) << k.method;
    EXPECT_EQ(status_of(answer), 405) << answer;
    EXPECT_NE(answer.find("\r\nAllow: " + k.allow + "\r\n"), std::string::npos) << answer;
    EXPECT_EQ(json::parse(body_of(answer), nullptr, false),
              json({{"error", "method not allowed: " + k.method + " " + k.path}}));
  }
  EXPECT_EQ(service->store().counts(id).running, 1);
}

TEST_F(RequestFraming, WellFramedRequestsShareAConnection) {
  start();
  const std::string body = sweep_request({"uct"}, {50}, {60}).dump();
  // A POST whose body ends exactly where Content-Length says, then two GETs, pipelined.
  const std::string answer =
      exchange("POST /api/v1/campaigns HTTP/1.1\r\n" + host() +
               "Content-Type: application/json\r\nContent-Length: " + std::to_string(body.size()) +
               "\r\n\r\n" + body + "GET /healthz HTTP/1.1\r\n" + host() +
               "Content-Length: 0\r\n\r\nGET /api/v1/campaigns/1 HTTP/1.1\r\n" + host() +
               "Connection: close\r\n\r\n");
  ASSERT_EQ(responses_in(answer), 3u) << answer;
  EXPECT_EQ(status_of(answer), 201) << answer;
  const auto second = answer.find("HTTP/1.1 ", 1);
  const auto third = answer.find("HTTP/1.1 ", second + 1);
  EXPECT_EQ(status_of(answer.substr(second)), 200);
  EXPECT_EQ(status_of(answer.substr(third)), 200);
  EXPECT_EQ(service->store().campaign_count(), 1);
}

}  // namespace
}  // namespace rockcal::test
