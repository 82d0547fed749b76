// The HTTP server: registers the route table, turns every error into the JSON error shape, checks
// the bearer token on mutating requests and caps body sizes.
#pragma once

#include <httplib.h>

#include <optional>
#include <string>

#include "api/routes.hpp"

namespace rockcal::api {

struct ServerConfig {
  std::string host = "127.0.0.1";
  int port = 8080;                   // 0: any free port (see ApiServer::bind)
  std::optional<std::string> token;  // when set, POST/DELETE need "Authorization: Bearer <token>"
  std::size_t max_body_bytes = 1 << 20;
  int http_threads = 32;
};

class ApiServer {
 public:
  ApiServer(orch::JobService& service, int workers, ServerConfig config);
  // Binds the listening socket; returns the port (useful with port 0). Throws if it cannot bind.
  int bind();
  // Serves until stop(); returns false on a socket error.
  bool listen() { return server_.listen_after_bind(); }
  void stop() { server_.stop(); }
  bool is_running() const { return server_.is_running(); }
  const std::vector<Route>& routes() const { return routes_; }

 private:
  bool authorized(const httplib::Request& req) const;

  ApiContext ctx_;
  ServerConfig config_;
  std::vector<Route> routes_;
  httplib::Server server_;
};

// Reads a token file (first line, surrounding whitespace trimmed); throws if missing or empty.
std::string read_token_file(const std::string& path);

}  // namespace rockcal::api
