#include "api/server/connections.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <system_error>

namespace rockcal::api {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

// Waits are cut into slices this long so that a stopping server ends its connections soon.
constexpr milliseconds kSlice{100};
// A connection over the cap is answered 503 if its request starts within kRefusalWait and arrives
// within kRefusalTimeout, else closed: the threads that answer them must not be held long.
constexpr milliseconds kRefusalWait{100};
constexpr milliseconds kRefusalTimeout{250};
constexpr std::size_t kRefusalThreads = 64;
// After answering a request whose body was left unread, the rest of what the client sends is read
// and dropped for up to this long (and this much) before closing: closing with unread data would
// reset the connection, and the client would lose the answer (typically a 413) with it.
constexpr milliseconds kLinger{1000};
constexpr std::size_t kLingerBytes = 16u << 20;

void linger(socket_t sock) {
  ::shutdown(sock, SHUT_WR);
  const auto until = Clock::now() + kLinger;
  std::size_t dropped = 0;
  char buffer[16384];
  while (dropped < kLingerBytes) {
    const auto left = std::chrono::duration_cast<milliseconds>(until - Clock::now());
    pollfd p{sock, POLLIN, 0};
    if (left.count() <= 0 || ::poll(&p, 1, static_cast<int>(left.count())) <= 0) return;
    const ssize_t n = ::recv(sock, buffer, sizeof buffer, 0);
    if (n <= 0) return;  // the client has closed its side too
    dropped += static_cast<std::size_t>(n);
  }
}

void address_of(const sockaddr_storage& a, std::string& ip, int& port) {
  char text[INET6_ADDRSTRLEN] = "";
  if (a.ss_family == AF_INET) {
    const auto& v4 = reinterpret_cast<const sockaddr_in&>(a);
    inet_ntop(AF_INET, &v4.sin_addr, text, sizeof text);
    port = ntohs(v4.sin_port);
  } else if (a.ss_family == AF_INET6) {
    const auto& v6 = reinterpret_cast<const sockaddr_in6&>(a);
    inet_ntop(AF_INET6, &v6.sin6_addr, text, sizeof text);
    port = ntohs(v6.sin6_port);
  }
  ip = text;
}

// A socket stream with a read buffer (httplib reads request heads a byte at a time), a deadline
// and a byte budget per request. Every wait also ends when the server stops listening.
class ConnectionStream : public httplib::Stream {
 public:
  ConnectionStream(socket_t sock, const ConnectionLimits& limits,
                   const std::atomic<socket_t>& listener)
      : sock_(sock), limits_(limits), listener_(listener) {}

  void begin_request(Clock::time_point deadline, std::size_t budget) {
    deadline_ = deadline;
    budget_ = budget;
  }

  // A read failed for time or size: the rest of the request is still on the wire, so the
  // connection cannot carry another one.
  bool cut_off() const { return cut_off_; }

  // Data waiting (buffered, or on the socket) within `timeout`: the start of the next request.
  bool wait_for_request(milliseconds timeout) {
    return begin_ < end_ || wait(POLLIN, Clock::now() + timeout);
  }

  bool is_readable() const override {
    return begin_ < end_ || wait(POLLIN, std::min(deadline_, Clock::now() + limits_.read_timeout));
  }
  bool is_writable() const override { return wait(POLLOUT, Clock::now() + limits_.write_timeout); }

  ssize_t read(char* ptr, size_t size) override {
    if (budget_ == 0) return cut();  // the request is larger than any this server accepts
    if (begin_ == end_) {
      if (!is_readable()) return cut();
      const ssize_t n = ::recv(sock_, buffer_, sizeof buffer_, 0);
      if (n <= 0) return n < 0 ? -1 : 0;
      begin_ = 0;
      end_ = static_cast<std::size_t>(n);
    }
    const std::size_t n = std::min({size, end_ - begin_, budget_});
    std::memcpy(ptr, buffer_ + begin_, n);
    begin_ += n;
    budget_ -= n;
    return static_cast<ssize_t>(n);
  }

  ssize_t write(const char* ptr, size_t size) override {
    if (!is_writable()) return -1;
    return ::send(sock_, ptr, size, MSG_NOSIGNAL);
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    sockaddr_storage a{};
    socklen_t len = sizeof a;
    if (getpeername(sock_, reinterpret_cast<sockaddr*>(&a), &len) == 0) address_of(a, ip, port);
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    sockaddr_storage a{};
    socklen_t len = sizeof a;
    if (getsockname(sock_, reinterpret_cast<sockaddr*>(&a), &len) == 0) address_of(a, ip, port);
  }
  socket_t socket() const override { return sock_; }

 private:
  ssize_t cut() {
    cut_off_ = true;
    return -1;
  }

  // Polls for `events` until `until`; false on timeout, error or a stopping server.
  bool wait(short events, Clock::time_point until) const {
    while (listener_.load() != INVALID_SOCKET) {
      const auto left = std::chrono::duration_cast<milliseconds>(until - Clock::now());
      if (left.count() <= 0) return false;
      pollfd p{sock_, events, 0};
      const int r = ::poll(&p, 1, static_cast<int>(std::min(left, kSlice).count()));
      if (r > 0) return true;  // ready, or hung up / failed: recv and send report which
      if (r < 0 && errno != EINTR) return false;
    }
    return false;
  }

  socket_t sock_;
  const ConnectionLimits& limits_;
  const std::atomic<socket_t>& listener_;
  Clock::time_point deadline_ = Clock::now();
  std::size_t budget_ = 0;
  char buffer_[4096];
  std::size_t begin_ = 0, end_ = 0;
  bool cut_off_ = false;
};

}  // namespace

ConnectionState& current_connection() {
  thread_local ConnectionState state;
  return state;
}

ConnectionThreads::~ConnectionThreads() {
  shutdown();
}

void ConnectionThreads::enqueue(std::function<void()> fn) {
  std::lock_guard lock(mutex_);
  tasks_.push_back(std::move(fn));
  if (idle_ < tasks_.size() && threads_.size() < max_threads_) {
    try {
      threads_.emplace_back([this] { work(); });
    } catch (const std::system_error&) {
      // No thread to be had now: the connection waits for one to come free.
    }
  }
  ready_.notify_one();
}

void ConnectionThreads::work() {
  std::unique_lock lock(mutex_);
  while (true) {
    ++idle_;
    ready_.wait(lock, [&] { return shutdown_ || !tasks_.empty(); });
    --idle_;
    if (tasks_.empty()) return;  // shut down, nothing left to serve
    std::function<void()> fn = std::move(tasks_.front());
    tasks_.pop_front();
    lock.unlock();
    try {
      fn();
    } catch (...) {
      // A connection's failure ends that connection only.
    }
    lock.lock();
  }
}

void ConnectionThreads::shutdown() {
  std::vector<std::thread> threads;
  {
    std::lock_guard lock(mutex_);
    shutdown_ = true;
    threads.swap(threads_);
  }
  ready_.notify_all();
  for (auto& t : threads) t.join();
}

void HttpServer::widen_backlog() {
  // httplib listens with a backlog of 5: a burst of connections overflows it, and the kernel then
  // drops connection attempts that clients retry only after 1, 3, 7 s. Listening again on a
  // listening socket only changes the backlog.
  if (svr_sock_ != INVALID_SOCKET) ::listen(svr_sock_, SOMAXCONN);
}

HttpServer::HttpServer(ConnectionLimits limits) : limits_(limits) {
  // One thread per connection, plus some to answer the connections over the cap.
  const std::size_t threads = limits_.max_connections + kRefusalThreads;
  new_task_queue = [threads] { return new ConnectionThreads(threads); };
}

bool HttpServer::process_and_close_socket(socket_t sock) {
  const std::size_t open = ++open_;
  ConnectionState& state = current_connection();
  state = ConnectionState{};
  state.over_capacity = open > limits_.max_connections;
  ConnectionStream stream(sock, limits_, svr_sock_);
  const milliseconds wait_first = state.over_capacity
                                      ? std::min(limits_.keep_alive_timeout, kRefusalWait)
                                      : limits_.keep_alive_timeout;
  const milliseconds request_timeout =
      state.over_capacity ? kRefusalTimeout : limits_.request_timeout;
  std::size_t left =
      state.over_capacity ? 1 : std::max<std::size_t>(1, limits_.keep_alive_max_count);
  bool ok = false;
  for (bool first = true; left > 0; --left, first = false) {
    if (!stream.wait_for_request(first ? wait_first : limits_.keep_alive_timeout)) break;
    stream.begin_request(Clock::now() + request_timeout, limits_.max_request_bytes);
    bool closed = false;
    ok = process_request(stream, left == 1, closed, nullptr);
    if (!ok || closed || state.close_after_response || stream.cut_off()) break;
  }
  if (state.close_after_response || stream.cut_off()) linger(sock);
  ::shutdown(sock, SHUT_RDWR);
  ::close(sock);
  --open_;
  return ok;
}

}  // namespace rockcal::api
