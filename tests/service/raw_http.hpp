// A raw TCP client for what no well-behaved HTTP client sends: chunked floods, heads that trickle
// in, bodies shorter than their Content-Length, connections that never send anything.
#pragma once

#include <chrono>
#include <string>
#include <string_view>

namespace rockcal::test {

class RawConnection {
 public:
  explicit RawConnection(int port);  // 127.0.0.1:port; throws if it cannot connect
  ~RawConnection();
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;

  // False once the peer has closed or reset the connection.
  bool send(std::string_view data);
  // Whether something (data, or the peer's close) is waiting to be read now.
  bool readable();
  // Whatever arrives until the peer closes the connection or `timeout` passes.
  std::string read(std::chrono::milliseconds timeout);
  // Whether the peer closed the connection within `timeout` (a reply before that is read and
  // dropped; see read()).
  bool closed_within(std::chrono::milliseconds timeout);

 private:
  std::string read_until_closed(std::chrono::milliseconds timeout, bool& closed);
  int fd_ = -1;
};

// 413 from "HTTP/1.1 413 Payload Too Large\r\n..."; 0 when there is no status line.
int status_of(const std::string& response);

// The JSON body of a raw response (after the blank line), or an empty string.
std::string body_of(const std::string& response);

}  // namespace rockcal::test
