#include "api/server.hpp"

#include <fstream>

#include "api/dashboard.hpp"
#include "api/http_util.hpp"
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

std::string default_message(int status, const httplib::Request& req, std::size_t max_body) {
  switch (status) {
    case 404:
      return "no such route: " + req.method + " " + req.path;
    case 405:
      return "method not allowed: " + req.method + " " + req.path;
    case 413:
      return "request body too large (the limit is " + std::to_string(max_body) + " bytes)";
    case 414:
      return "request URI too long";
    case 400:
      return "bad request";
    default:
      return "HTTP error " + std::to_string(status);
  }
}

}  // namespace

ApiServer::ApiServer(orch::JobService& service, int workers, ServerConfig config)
    : ctx_{service, workers}, config_(std::move(config)) {
  routes_ = api_routes(ctx_);
  int threads = config_.http_threads;
  server_.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  server_.set_payload_max_length(config_.max_body_bytes);
  server_.set_keep_alive_max_count(100);
  server_.set_keep_alive_timeout(2);  // keep-alive connections pin pool threads; release them soon
  server_.set_read_timeout(10, 0);
  server_.set_write_timeout(10, 0);

  server_.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    if (is_mutating(req.method) && !authorized(req)) {
      res.set_header("WWW-Authenticate", "Bearer");
      send_error(res, 401, "missing or wrong bearer token (Authorization: Bearer <token>)",
                 "Authorization");
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });

  for (const auto& route : routes_) {
    auto wrapped = [handler = route.handler](const httplib::Request& req, httplib::Response& res) {
      try {
        handler(req, res);
      } catch (const HttpError& e) {
        send_error(res, e.status, e.what(), e.field);
      } catch (const orch::RequestError& e) {
        send_error(res, 400, e.what(), e.field);
      }
    };
    std::string pattern = path_regex(route.path);
    if (route.method == "GET") server_.Get(pattern, wrapped);
    if (route.method == "POST") server_.Post(pattern, wrapped);
    if (route.method == "DELETE") server_.Delete(pattern, wrapped);
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

bool ApiServer::authorized(const httplib::Request& req) const {
  if (!config_.token) return true;
  std::string header = req.get_header_value("Authorization");
  const std::string prefix = "Bearer ";
  if (header.rfind(prefix, 0) != 0) return false;
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
