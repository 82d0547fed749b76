#include "api/server/framing.hpp"

#include <algorithm>
#include <cctype>

namespace rockcal::api {
namespace {

bool all_digits(const std::string& s) {
  return !s.empty() && s.size() <= 19 && std::all_of(s.begin(), s.end(), [](char ch) {
    return std::isdigit(static_cast<unsigned char>(ch));
  });
}

std::string lower(std::string s) {
  for (char& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

std::vector<std::string> values_of(const httplib::Request& req, const std::string& name) {
  std::vector<std::string> out;
  const auto range = req.headers.equal_range(name);
  for (auto it = range.first; it != range.second; ++it) out.push_back(it->second);
  return out;
}

}  // namespace

bool takes_body(const std::string& method) {
  return method == "POST";
}

std::optional<HttpError> framing_error(const httplib::Request& req) {
  const std::vector<std::string> lengths = values_of(req, "Content-Length");
  const std::vector<std::string> encodings = values_of(req, "Transfer-Encoding");
  for (const auto& length : lengths) {
    if (!all_digits(length)) {
      return HttpError(400,
                       "Content-Length must be a decimal number of bytes (got '" + length + "')",
                       "Content-Length");
    }
  }
  for (const auto& length : lengths) {
    if (std::stoull(length) != std::stoull(lengths.front())) {
      return HttpError(
          400, "conflicting Content-Length headers (" + lengths.front() + " and " + length + ")",
          "Content-Length");
    }
  }
  if (encodings.size() > 1 || (encodings.size() == 1 && lower(encodings.front()) != "chunked")) {
    std::string given;
    for (const auto& e : encodings) given += (given.empty() ? "" : ", ") + e;
    return HttpError(400, "Transfer-Encoding must be chunked alone (got '" + given + "')",
                     "Transfer-Encoding");
  }
  if (!encodings.empty() && !lengths.empty()) {
    return HttpError(400, "a request may not have both Content-Length and Transfer-Encoding",
                     "Transfer-Encoding");
  }
  const bool has_body =
      !encodings.empty() || (!lengths.empty() && std::stoull(lengths.front()) > 0);
  if (has_body && !takes_body(req.method)) {
    return HttpError(400, req.method + " requests take no body", "(body)");
  }
  return std::nullopt;
}

}  // namespace rockcal::api
