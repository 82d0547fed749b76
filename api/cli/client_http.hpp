// What the client commands share: an HTTP client for `--server` with the bearer token, the error
// report of a failed request, a campaign's one-line status, and column padding for tables.
#pragma once

#include <httplib.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "api/cli/client.hpp"

namespace rockcal::api {

struct Http {
  std::string server;  // the URL, for messages
  httplib::Client client;
  httplib::Headers headers;
  explicit Http(const ClientOptions& o);
  // Prints the server's error (or the transport error, naming the URL) and returns the exit code
  // to use.
  int report(const httplib::Result& r) const;
  // watch_campaign() over GET /api/v1/campaigns/{id}: returns the last campaign object, or nullopt
  // after reporting a failed request (`exit_code` set).
  std::optional<nlohmann::json> watch(std::int64_t id, bool wait, int progress_fd, int& exit_code);
};

// The campaign object as GET /api/v1/campaigns/{id} gives it, or nullopt when it cannot be had
// (the fetch has reported why).
using CampaignFetch = std::function<std::optional<nlohmann::json>()>;

// The one wait loop of the client commands (rockcal status --wait, rockcal diagnose over HTTP;
// rockcal twin over its own service): fetches the campaign until it has ended (once without
// `wait`), showing progress_line() on `progress_fd` (redrawn on a terminal, paced lines in a log).
// Returns the last campaign object, or nullopt when a fetch failed.
std::optional<nlohmann::json> watch_campaign(const CampaignFetch& fetch, bool wait,
                                             int progress_fd);

// `text` padded to `width` columns (UTF-8: "±" is two bytes, one column).
std::string padded(std::string text, std::size_t width);

// "campaign 3 running [####....] 45% 12/27 done, 2 running, ..." for GET /campaigns/{id}.
std::string status_line(const nlohmann::json& campaign);

}  // namespace rockcal::api
