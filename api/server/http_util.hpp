// Small helpers for handlers: JSON replies, errors in the one shape clients parse, parameters.
#pragma once

#include <httplib.h>

#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "db/storage_faults.hpp"

namespace rockcal::api {

// Thrown by handlers; the server turns it into {"error": ..., "field": ...} with `status`.
struct HttpError : std::runtime_error {
  int status;
  std::string field;
  HttpError(int status_code, const std::string& message, std::string field_name = "")
      : std::runtime_error(message), status(status_code), field(std::move(field_name)) {}
};

void send_json(httplib::Response& res, const nlohmann::json& body, int status = 200);
void send_error(httplib::Response& res, int status, const std::string& message,
                const std::string& field = "");

// A storage fault (db/storage_faults.hpp) as the answer to a request: 503 with Retry-After for a
// busy database or an I/O error, 507 for a full one; the error names the kind and SQLite's reason.
void send_storage_fault(httplib::Response& res, const db::StorageFault& fault);

// A positive decimal id from a path segment in canonical form (no sign, no leading zero); anything
// else (e.g. "../x", "01") is a 400.
std::int64_t parse_id(const std::string& text, const std::string& what);

// Optional query parameters, validated (400 naming the parameter when malformed). Which parameters
// a route takes, and that none is given twice, the server checks (Route::params).
std::optional<double> query_number(const httplib::Request& req, const std::string& name);
std::int64_t query_int(const httplib::Request& req, const std::string& name, std::int64_t fallback,
                       std::int64_t min, std::int64_t max);

// Shortest text that reads back as the same double.
std::string number_text(double x);

}  // namespace rockcal::api
