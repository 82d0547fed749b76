// The command-line client: talks HTTP to a rockcal server (`--server URL`).
#pragma once

#include <cstdint>
#include <string>

namespace rockcal::api {

struct ClientOptions {
  std::string server = "http://127.0.0.1:8080";
  std::string token_file;  // or the ROCKCAL_TOKEN environment variable
};

int client_submit(const ClientOptions& o, const std::string& file);
int client_status(const ClientOptions& o, std::int64_t campaign_id, bool wait);
int client_results(const ClientOptions& o, std::int64_t campaign_id, bool csv);
int client_cancel(const ClientOptions& o, std::int64_t campaign_id);
int client_list(const ClientOptions& o);

// "[#########.........] 45%" for a fraction in [0, 1].
std::string progress_bar(double fraction, int width);

}  // namespace rockcal::api
