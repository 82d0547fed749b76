#include "api/server/http_util.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace rockcal::api {

void send_json(httplib::Response& res, const nlohmann::json& body, int status) {
  res.status = status;
  // "replace": a stored string with invalid UTF-8 must not turn a reply into a 500.
  res.set_content(body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n",
                  "application/json");
}

void send_error(httplib::Response& res, int status, const std::string& message,
                const std::string& field) {
  nlohmann::json body = {{"error", message}};
  if (!field.empty()) body["field"] = field;
  send_json(res, body, status);
}

void send_storage_fault(httplib::Response& res, const db::StorageFault& fault) {
  if (fault.kind != "full") res.set_header("Retry-After", "1");
  send_error(res, fault.kind == "full" ? 507 : 503,
             "storage " + fault.kind + ": " + fault.message +
                 (fault.kind == "full" ? "; nothing was stored" : "; retry shortly"));
}

std::int64_t parse_id(const std::string& text, const std::string& what) {
  std::int64_t value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  // Canonical form only: "01" is not another name for job 1.
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || value <= 0 ||
      text[0] == '0' || !std::isdigit(static_cast<unsigned char>(text[0]))) {
    throw HttpError(400, what + " must be a positive integer without leading zeros", "id");
  }
  return value;
}

std::optional<double> query_number(const httplib::Request& req, const std::string& name) {
  if (!req.has_param(name.c_str())) return std::nullopt;
  std::string text = req.get_param_value(name.c_str());
  double value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() ||
      !std::isfinite(value)) {
    throw HttpError(400, "query parameter '" + name + "' must be a finite number", name);
  }
  return value;
}

std::int64_t query_int(const httplib::Request& req, const std::string& name, std::int64_t fallback,
                       std::int64_t min, std::int64_t max) {
  if (!req.has_param(name.c_str())) return fallback;
  std::string text = req.get_param_value(name.c_str());
  std::int64_t value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || value < min ||
      value > max) {
    throw HttpError(400,
                    "query parameter '" + name + "' must be an integer in [" + std::to_string(min) +
                        ", " + std::to_string(max) + "]",
                    name);
  }
  return value;
}

std::string number_text(double x) {
  char buf[64];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);
  return ec == std::errc() ? std::string(buf, end) : std::string("nan");
}

}  // namespace rockcal::api
