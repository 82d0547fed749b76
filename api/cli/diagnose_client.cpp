// `rockcal diagnose FILE`: a diagnosis campaign from submission to verdict table and HTML page.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "api/cli/client.hpp"
#include "api/cli/client_http.hpp"
#include "api/cli/diagnosis_text.hpp"
#include "api/cli/status_text.hpp"
#include "engine/json_input.hpp"
#include "orchestrator/summary_reader.hpp"

namespace rockcal::api {
namespace {

using nlohmann::json;
using summary::at;

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The request as the server takes it: kind filled in, a dataset file read and inlined.
json diagnosis_request(const std::string& file) {
  json request = parse_json_input(read_file(file));
  if (!request.is_object()) throw std::runtime_error(file + ": not a JSON object");
  if (!request.contains("kind")) request["kind"] = "diagnosis";
  if (request.contains("dataset_file")) {
    if (!request["dataset_file"].is_string()) throw std::runtime_error("dataset_file: not a path");
    std::filesystem::path path = request["dataset_file"].get<std::string>();
    if (path.is_relative()) path = std::filesystem::path(file).parent_path() / path;
    const std::string text = read_file(path);
    if (path.extension() == ".csv") {
      request["dataset_csv"] = text;
    } else {
      request["dataset"] = parse_json_input(text);
    }
    request.erase("dataset_file");
  }
  return request;
}

}  // namespace

int client_diagnose(const ClientOptions& o, const std::string& file, const std::string& html_out) {
  const json request = diagnosis_request(file);
  Http http(o);
  auto posted =
      http.client.Post("/api/v1/campaigns", http.headers, request.dump(), "application/json");
  if (!posted || posted->status != 201) return http.report(posted);
  const std::int64_t id = json::parse(posted->body)["id"].get<std::int64_t>();
  const std::string path = "/api/v1/campaigns/" + std::to_string(id);
  std::cout << "diagnosis campaign " << id << std::endl;
  // The campaign's state follows its driver: it ends when the driver has (campaign_status.hpp).
  int exit_code = 0;
  const auto watched = http.watch(id, true, STDOUT_FILENO, exit_code);
  if (!watched) return exit_code;
  const json& c = *watched;
  std::cout << progress_line(c) << std::endl;
  if (c.value("driver_status", "") != "done") {
    std::cerr << "rockcal: diagnosis " << id << " did not finish: " << at(c, "summary").dump()
              << "\n";
    return 1;
  }
  std::cout << "\n" << diagnosis_text(c["summary"]);
  auto page = http.client.Get(path + "/report.html", http.headers);
  if (!page || page->status != 200) return http.report(page);
  const std::string out = html_out.empty() ? "diagnosis-" + std::to_string(id) + ".html" : html_out;
  std::ofstream(out) << page->body;
  std::cout << "\nreport: " << out << "\n";
  return 0;
}

}  // namespace rockcal::api
