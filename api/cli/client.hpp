// The command-line client: talks HTTP to a rockcal server (`--server URL`).
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

namespace rockcal::api {

struct ClientOptions {
  std::string server = "http://127.0.0.1:8080";
  std::string token_file;  // or the ROCKCAL_TOKEN environment variable
};

int client_submit(const ClientOptions& o, const std::string& file);
// Prints the campaign's progress line (with `wait`: redrawn on a terminal, a paced log otherwise,
// until it ends) and, once it has ended, its summary (status_text.hpp); `as_json` prints the
// campaign object instead (progress lines, if waiting, on stderr).
int client_status(const ClientOptions& o, std::int64_t campaign_id, bool wait, bool as_json);
int client_results(const ClientOptions& o, std::int64_t campaign_id, bool csv);
int client_cancel(const ClientOptions& o, std::int64_t campaign_id);
int client_list(const ClientOptions& o);

// `rockcal diagnose FILE`: submits a diagnosis request (FILE's "dataset_file", relative to FILE, is
// read here and sent inline: the server reads no files), shows its progress, prints the verdict
// table and writes the HTML report to `html_out` (default diagnosis-<id>.html).
int client_diagnose(const ClientOptions& o, const std::string& file, const std::string& html_out);

// A campaign's results (GET .../results) as a table: one row per test and point with n, failed
// realisations and mean ± standard error of peak load, strength and Young's modulus, then the
// realisations without values and why.
std::string results_text(const nlohmann::json& results_body);

// "[#########.........] 45%" for a fraction in [0, 1].
std::string progress_bar(double fraction, int width);

}  // namespace rockcal::api
