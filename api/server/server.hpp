// The HTTP server: registers the route table, turns every error into the JSON error shape, refuses
// requests of ambiguous framing (api/server/framing.hpp) and methods no route takes (405), checks
// Host (and Origin) against the allowed hosts, the bearer token and Content-Type on mutating
// requests and the query parameters of each route, and caps body sizes and connections.
#pragma once

#include <httplib.h>

#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "api/server/connections.hpp"
#include "api/server/routes.hpp"

namespace rockcal::api {

struct ServerConfig {
  std::string host = "127.0.0.1";
  int port = 8080;                   // 0: any free port (see ApiServer::bind)
  std::optional<std::string> token;  // when set, POST/DELETE need "Authorization: Bearer <token>"
  // With a token: reads of /api/ and /metrics need it too (beyond loopback, the data is not
  // everyone's); /healthz and the dashboard's files stay open.
  bool protect_reads = false;
  std::size_t max_body_bytes = 1 << 20;
  // Host header values served, as "name" (with the bound port) or "name:port"; "*" serves any.
  // Empty: the listen address's names (allowed_hosts_for), so that a web page in a browser cannot
  // reach the server under a name of its own (DNS rebinding).
  std::vector<std::string> allowed_hosts;
  ConnectionLimits connections;  // max_request_bytes is derived from max_body_bytes
};

// The default allowed hosts for a listen address: loopback names for a loopback address, the
// address itself otherwise, plus this machine's host name and interface addresses for a wildcard
// address (0.0.0.0 or ::).
std::vector<std::string> allowed_hosts_for(const std::string& listen_host);

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
  std::size_t open_connections() const { return server_.open_connections(); }

 private:
  bool authorized(const httplib::Request& req) const;
  bool host_allowed(const std::string& host) const;
  // The methods the routes at `path` answer, for a 405's Allow header.
  std::string allowed_methods(const std::string& path) const;
  // Answers requests the route handlers must not see (over the connection cap, ambiguous framing,
  // a method no route takes, wrong Host, token or Content-Type, too large); true when it did.
  bool refused(const httplib::Request& req, httplib::Response& res) const;

  ApiContext ctx_;
  ServerConfig config_;
  std::vector<Route> routes_;
  std::vector<std::regex> route_patterns_;  // path_regex of each route, in the same order
  HttpServer server_;
  int bound_port_ = 0;
  std::vector<std::string> default_hosts_;  // allowed_hosts_for(host), set by bind()
};

// Reads a token file (first line, surrounding whitespace trimmed); throws if missing or empty.
std::string read_token_file(const std::string& path);

}  // namespace rockcal::api
