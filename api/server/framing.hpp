// Request framing: where one request ends and the next begins on a kept-alive connection. The
// server serves only requests whose end it and every proxy in front of it agree on: a request
// that could be read two ways (a body on a GET that httplib would read as the next request,
// conflicting or malformed Content-Length headers, a Transfer-Encoding other than chunked, both
// framings at once) is refused before its body is read, and its connection is closed.
#pragma once

#include <httplib.h>

#include <optional>

#include "api/server/http_util.hpp"

namespace rockcal::api {

// The methods whose requests carry a body here (POST); any other must not have one.
bool takes_body(const std::string& method);

// Why the request's framing is refused (a 400 naming the header, or "(body)"), or nothing.
std::optional<HttpError> framing_error(const httplib::Request& req);

}  // namespace rockcal::api
