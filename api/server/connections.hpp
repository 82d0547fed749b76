// The HTTP connection layer under the routes. cpp-httplib 0.11.4 serves each connection on one
// thread of a fixed pool, reads with a per-read timeout only and caps only bodies that carry a
// Content-Length: a few dozen idle or slow clients hold every thread (a client sending one header
// line every 8 s is never cut off), and a chunked body has no limit. HttpServer replaces the
// library's per-connection loop (process_and_close_socket, a virtual that its SSLServer overrides
// the same way) and keeps its request parsing and routing:
// - one thread per open connection, up to max_connections; a connection over the cap gets a 503
//   (through the pre-routing handler, see current_connection()) and is closed;
// - a deadline for each whole request (head and body) besides the per-read timeout;
// - a byte budget for each request whatever its transfer encoding;
// - idle keep-alive connections are closed after keep_alive_timeout; stop() ends every
//   connection within about 0.1 s.
#pragma once

#include <httplib.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace rockcal::api {

struct ConnectionLimits {
  std::size_t max_connections = 512;
  std::chrono::milliseconds read_timeout{5000};        // one read may wait this long for data
  std::chrono::milliseconds write_timeout{10000};      // one write may wait this long
  std::chrono::milliseconds request_timeout{20000};    // a whole request must arrive within this
  std::chrono::milliseconds keep_alive_timeout{5000};  // an idle connection is closed after this
  std::size_t keep_alive_max_count = 100;              // requests per connection
  std::size_t max_request_bytes = (1u << 20) + (64u << 10);  // head + body of one request
};

// What the connection layer tells the handlers about the connection of the request being served
// on this thread (each connection has its own thread).
struct ConnectionState {
  bool over_capacity = false;         // the pre-routing handler answers 503
  bool close_after_response = false;  // set by a handler that left the body unread
};
ConnectionState& current_connection();

// Runs each task (a connection) on a thread of its own: threads are started as connections
// arrive, kept for reuse, and never more than max_threads (further tasks wait for one).
class ConnectionThreads : public httplib::TaskQueue {
 public:
  explicit ConnectionThreads(std::size_t max_threads) : max_threads_(max_threads) {}
  ~ConnectionThreads() override;
  void enqueue(std::function<void()> fn) override;
  void shutdown() override;

 private:
  void work();

  std::size_t max_threads_;
  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<std::function<void()>> tasks_;
  std::vector<std::thread> threads_;
  std::size_t idle_ = 0;
  bool shutdown_ = false;
};

class HttpServer : public httplib::Server {
 public:
  explicit HttpServer(ConnectionLimits limits);
  const ConnectionLimits& limits() const { return limits_; }
  // Connections open now (including ones being refused over the cap).
  std::size_t open_connections() const { return open_.load(); }
  // Call after binding: a listen backlog for bursts of connections.
  void widen_backlog();

 private:
  bool process_and_close_socket(socket_t sock) override;

  ConnectionLimits limits_;
  std::atomic<std::size_t> open_{0};
};

}  // namespace rockcal::api
