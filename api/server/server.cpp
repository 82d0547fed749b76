#include "api/server/server.hpp"

#include <ifaddrs.h>
#include <netdb.h>
#include <netinet/in.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <fstream>

#include "api/server/dashboard.hpp"
#include "api/server/framing.hpp"
#include "api/server/http_util.hpp"
#include "orchestrator/request_error.hpp"

namespace rockcal::api {

namespace {

// Compares without an early exit, so response time does not reveal how much of a token matched.
bool same_secret(const std::string& given, const std::string& secret) {
  if (secret.empty() || given.size() != secret.size()) return false;
  unsigned char diff = 0;
  for (std::size_t i = 0; i < given.size(); ++i) diff |= given[i] ^ secret[i];
  return diff == 0;
}

bool is_mutating(const std::string& method) {
  return method != "GET" && method != "HEAD" && method != "OPTIONS";
}

std::string lower(std::string s) {
  for (char& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

std::string too_large_message(std::size_t max_body) {
  return "request body too large (the limit is " + std::to_string(max_body) + " bytes)";
}

std::string default_message(int status, const httplib::Request& req, std::size_t max_body) {
  switch (status) {
    case 404:
      return "no such route: " + req.method + " " + req.path;
    case 405:
      return "method not allowed: " + req.method + " " + req.path;
    case 413:
      return too_large_message(max_body);
    case 414:
      return "request URI too long";
    case 400:
      return "bad request";
    default:
      return "HTTP error " + std::to_string(status);
  }
}

// "::1" -> "[::1]": IPv6 literals appear bracketed in Host headers.
std::string host_form(const std::string& name) {
  const bool ipv6 = std::count(name.begin(), name.end(), ':') > 1 && name.front() != '[';
  return lower(ipv6 ? "[" + name + "]" : name);
}

bool is_loopback(const std::string& host) {
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

// The media type of a Content-Type value, without parameters ("; charset=utf-8").
std::string media_type(const std::string& content_type) {
  std::string type = content_type.substr(0, content_type.find(';'));
  const auto first = type.find_first_not_of(" \t");
  const auto last = type.find_last_not_of(" \t");
  return first == std::string::npos ? "" : lower(type.substr(first, last - first + 1));
}

// Refuses query parameters the route does not take, and any given twice (which of two values
// counts is nowhere written down).
void check_params(const httplib::Request& req, const std::vector<std::string>& known) {
  for (auto it = req.params.begin(); it != req.params.end();
       it = req.params.upper_bound(it->first)) {
    const std::string& key = it->first;
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      std::string names;
      for (const auto& k : known) names += (names.empty() ? "" : ", ") + k;
      throw HttpError(400,
                      "unknown query parameter '" + key + "' (" +
                          (known.empty() ? "this route takes none" : "known: " + names) + ")",
                      key);
    }
    if (req.params.count(key) > 1) {
      throw HttpError(400, "query parameter '" + key + "' is given more than once", key);
    }
  }
}

void send_unauthorized(httplib::Response& res) {
  res.set_header("WWW-Authenticate", "Bearer");
  send_error(res, 401, "missing or wrong bearer token (Authorization: Bearer <token>)",
             "Authorization");
}

// The data a protected server serves only with the token (see ServerConfig::protect_reads).
bool reads_need_token(const std::string& path) {
  return path.rfind("/api/", 0) == 0 || path == "/metrics";
}

ConnectionLimits limits_of(const ServerConfig& c) {
  ConnectionLimits l = c.connections;
  l.max_request_bytes = c.max_body_bytes + (64u << 10);  // the body plus a generous head
  return l;
}

}  // namespace

std::vector<std::string> allowed_hosts_for(const std::string& listen_host) {
  std::vector<std::string> out;
  auto add = [&](const std::string& name) {
    if (!name.empty() && std::find(out.begin(), out.end(), host_form(name)) == out.end())
      out.push_back(host_form(name));
  };
  const bool wildcard = listen_host.empty() || listen_host == "0.0.0.0" || listen_host == "::";
  if (wildcard || is_loopback(listen_host)) {
    for (const char* name : {"localhost", "127.0.0.1", "::1"}) add(name);
  }
  if (!wildcard) add(listen_host);
  if (!is_loopback(listen_host)) {
    char name[256] = "";
    if (gethostname(name, sizeof name - 1) == 0) add(name);
  }
  if (wildcard) {
    ifaddrs* list = nullptr;
    if (getifaddrs(&list) == 0) {
      for (ifaddrs* a = list; a; a = a->ifa_next) {
        if (!a->ifa_addr ||
            (a->ifa_addr->sa_family != AF_INET && a->ifa_addr->sa_family != AF_INET6))
          continue;
        const socklen_t len =
            a->ifa_addr->sa_family == AF_INET ? sizeof(sockaddr_in) : sizeof(sockaddr_in6);
        char text[NI_MAXHOST] = "";
        if (getnameinfo(a->ifa_addr, len, text, sizeof text, nullptr, 0, NI_NUMERICHOST) == 0 &&
            std::string(text).find('%') ==
                std::string::npos)  // link-local addresses with a zone: not in URLs
          add(text);
      }
      freeifaddrs(list);
    }
  }
  return out;
}

ApiServer::ApiServer(orch::JobService& service, int workers, ServerConfig config)
    : ctx_{service, workers}, config_(std::move(config)), server_(limits_of(config_)) {
  routes_ = api_routes(ctx_);
  const ConnectionLimits& limits = server_.limits();
  server_.set_payload_max_length(config_.max_body_bytes);
  // HttpServer enforces these; httplib puts the keep-alive ones in its Keep-Alive response header
  // and the timeouts on each accepted socket (SO_RCVTIMEO, SO_SNDTIMEO).
  server_.set_keep_alive_max_count(limits.keep_alive_max_count);
  server_.set_keep_alive_timeout(
      std::chrono::duration_cast<std::chrono::seconds>(limits.keep_alive_timeout).count());
  server_.set_read_timeout(limits.read_timeout);
  server_.set_write_timeout(limits.write_timeout);

  server_.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    if (!refused(req, res)) return httplib::Server::HandlerResponse::Unhandled;
    // The body (if any) stays unread: the connection cannot carry another request.
    current_connection().close_after_response = true;
    res.set_header("Connection", "close");
    return httplib::Server::HandlerResponse::Handled;
  });

  for (const auto& route : routes_) {
    auto run = [this, handler = route.handler, params = route.params](const httplib::Request& req,
                                                                      httplib::Response& res) {
      try {
        check_params(req, params);
        handler(req, res);
      } catch (const HttpError& e) {
        send_error(res, e.status, e.what(), e.field);
      } catch (const orch::RequestError& e) {
        send_error(res, 400, e.what(), e.field);
      } catch (const db::SqliteError& e) {
        const std::string kind = ctx_.service.store().note_failure(e);
        if (kind.empty()) throw;  // not the storage: a 500
        send_storage_fault(res, {kind, sqlite3_errstr(e.code)});
      }
    };
    std::string pattern = path_regex(route.path);
    route_patterns_.emplace_back(pattern);
    if (route.method == "GET") server_.Get(pattern, run);
    if (route.method == "DELETE") server_.Delete(pattern, run);
    if (route.method == "POST") {
      // The body is read here, so that its limit holds for every transfer encoding (httplib caps
      // only a declared Content-Length) and is enforced while reading.
      server_.Post(pattern, [this, run](const httplib::Request& req, httplib::Response& res,
                                        const httplib::ContentReader& read) {
        std::string body;
        bool too_large = false;
        const bool complete = read([&](const char* data, std::size_t n) {
          too_large = body.size() + n > config_.max_body_bytes;
          if (!too_large) body.append(data, n);
          return !too_large;
        });
        if (too_large || !complete) {
          current_connection().close_after_response = true;
          res.set_header("Connection", "close");
          if (too_large) return send_error(res, 413, too_large_message(config_.max_body_bytes));
          return send_error(res, 400, "request body incomplete", "(body)");
        }
        // A copy with the body: its `matches` still point into `req`, which outlives the call.
        httplib::Request with_body = req;
        with_body.body = std::move(body);
        run(with_body, res);
      });
    }
  }

  mount_dashboard(server_);

  // Unrouted paths, oversized bodies and the like: httplib sets the status; we add the JSON body.
  server_.set_error_handler(httplib::Server::HandlerWithResponse(
      [this](const httplib::Request& req, httplib::Response& res) {
        if (res.body.empty())
          send_error(res, res.status, default_message(res.status, req, config_.max_body_bytes));
        return httplib::Server::HandlerResponse::Handled;
      }));
  server_.set_exception_handler(
      [](const httplib::Request&, httplib::Response& res, std::exception_ptr ep) {
        std::string what = "internal error";
        try {
          std::rethrow_exception(ep);
        } catch (const std::exception& e) {
          what = std::string("internal error: ") + e.what();
        } catch (...) {
        }
        send_error(res, 500, what);
      });
}

bool ApiServer::refused(const httplib::Request& req, httplib::Response& res) const {
  const ConnectionLimits& limits = server_.limits();
  if (current_connection().over_capacity) {
    res.set_header("Retry-After", "1");
    send_error(res, 503,
               "too many open connections (the limit is " + std::to_string(limits.max_connections) +
                   "); retry shortly");
    return true;
  }
  if (auto error = framing_error(req)) {
    send_error(res, error->status, error->what(), error->field);
    return true;
  }
  if (req.method != "GET" && req.method != "HEAD" && req.method != "POST" &&
      req.method != "DELETE") {
    res.set_header("Allow", allowed_methods(req.path));
    send_error(res, 405, default_message(405, req, config_.max_body_bytes));
    return true;
  }
  const std::string host = req.get_header_value("Host");
  if (!host_allowed(host)) {
    send_error(res, 403,
               host.empty() ? "the Host header is required"
                            : "Host '" + host + "' is not served here (see --allowed-hosts)",
               "Host");
    return true;
  }
  if (is_mutating(req.method)) {
    // A browser names the page that sent a request; a page of another site must not drive us.
    if (req.has_header("Origin")) {
      const std::string origin = req.get_header_value("Origin");
      const auto scheme_end = origin.find("://");
      if (scheme_end == std::string::npos || !host_allowed(origin.substr(scheme_end + 3))) {
        send_error(res, 403, "Origin '" + origin + "' may not send " + req.method + " requests",
                   "Origin");
        return true;
      }
    }
    if (!authorized(req)) {
      send_unauthorized(res);
      return true;
    }
    // A cross-site HTML form can post text/plain without asking; it cannot post JSON.
    if (req.method == "POST" &&
        media_type(req.get_header_value("Content-Type")) != "application/json") {
      send_error(res, 415,
                 "Content-Type must be application/json (got '" +
                     req.get_header_value("Content-Type") + "')",
                 "Content-Type");
      return true;
    }
  }
  if (!is_mutating(req.method) && config_.protect_reads && reads_need_token(req.path) &&
      !authorized(req)) {
    send_unauthorized(res);
    return true;
  }
  if (req.get_header_value<std::uint64_t>("Content-Length") > config_.max_body_bytes) {
    send_error(res, 413, too_large_message(config_.max_body_bytes));
    return true;
  }
  return false;
}

std::string ApiServer::allowed_methods(const std::string& path) const {
  std::string out;
  for (std::size_t i = 0; i < routes_.size(); ++i) {
    if (!std::regex_match(path, route_patterns_[i])) continue;
    const std::string& method = routes_[i].method;
    out += (out.empty() ? "" : ", ") + (method == "GET" ? std::string("GET, HEAD") : method);
  }
  return out.empty() ? "GET, HEAD" : out;  // the dashboard's pages, and 404s
}

bool ApiServer::host_allowed(const std::string& given) const {
  if (given.empty()) return false;
  const std::string host = lower(given);
  const std::string port = std::to_string(bound_port_);
  const std::vector<std::string>& allowed =
      config_.allowed_hosts.empty() ? default_hosts_ : config_.allowed_hosts;
  return std::any_of(allowed.begin(), allowed.end(), [&](const std::string& entry) {
    if (entry == "*") return true;
    const std::string name = host_form(entry);
    const auto colon = name.rfind(':'), bracket = name.rfind(']');
    const bool has_port =
        colon != std::string::npos && (bracket == std::string::npos || colon > bracket);
    if (has_port) return host == name;
    return host == name + ":" + port || (bound_port_ == 80 && host == name);
  });
}

bool ApiServer::authorized(const httplib::Request& req) const {
  if (!config_.token) return true;
  std::string header = req.get_header_value("Authorization");
  const std::string prefix = "bearer ";  // the scheme is case-insensitive (RFC 7235)
  if (lower(header.substr(0, prefix.size())) != prefix) return false;
  return same_secret(header.substr(prefix.size()), *config_.token);
}

int ApiServer::bind() {
  int port = config_.port;
  if (port == 0) {
    port = server_.bind_to_any_port(config_.host);
  } else if (!server_.bind_to_port(config_.host, port)) {
    port = -1;
  }
  if (port <= 0) {
    throw std::runtime_error("cannot listen on " + config_.host + ":" +
                             std::to_string(config_.port));
  }
  server_.widen_backlog();
  bound_port_ = port;
  default_hosts_ = allowed_hosts_for(config_.host);
  return port;
}

std::string read_token_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read token file " + path);
  std::string token;
  std::getline(in, token);
  auto first = token.find_first_not_of(" \t\r\n");
  auto last = token.find_last_not_of(" \t\r\n");
  if (first == std::string::npos) throw std::runtime_error("token file " + path + " is empty");
  return token.substr(first, last - first + 1);
}

}  // namespace rockcal::api
