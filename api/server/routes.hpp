// The REST API v1 as a table: one entry per route. The server registers exactly these, and a test
// checks them against api/openapi.yaml.
#pragma once

#include <httplib.h>

#include <string>
#include <vector>

#include "orchestrator/job_service.hpp"

namespace rockcal::api {

struct Route {
  std::string method;  // GET | POST | DELETE
  std::string path;    // OpenAPI template, e.g. /api/v1/jobs/{id}
  httplib::Server::Handler handler;
  // The query parameters it takes; the server refuses any other, and any given twice.
  std::vector<std::string> params = {};
};

struct ApiContext {
  orch::JobService& service;
  int workers;  // for ETAs and /metrics
};

std::vector<Route> api_routes(ApiContext& ctx);

// "/api/v1/jobs/{id}/log" -> "/api/v1/jobs/([^/]+)/log": one path segment per parameter.
std::string path_regex(const std::string& path_template);

}  // namespace rockcal::api
