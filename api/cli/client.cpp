#include "api/cli/client.hpp"

#include <httplib.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "api/cli/client_http.hpp"
#include "api/cli/status_text.hpp"
#include "api/server/server.hpp"

namespace rockcal::api {

using nlohmann::json;

Http::Http(const ClientOptions& o) : server(o.server), client(o.server) {
  client.set_connection_timeout(5, 0);
  client.set_read_timeout(60, 0);
  std::string token;
  if (!o.token_file.empty()) {
    token = read_token_file(o.token_file);
  } else if (const char* env = std::getenv("ROCKCAL_TOKEN")) {
    token = env;
  }
  if (!token.empty()) headers.emplace("Authorization", "Bearer " + token);
}

// Prints the server's error (or the transport error) and returns the exit code to use.
int Http::report(const httplib::Result& r) const {
  if (!r) {
    std::cerr << "rockcal: cannot reach the server at " << server << " ("
              << httplib::to_string(r.error())
              << " error; give its URL with --server or $ROCKCAL_SERVER)\n";
    return 2;
  }
  json body = json::parse(r->body, nullptr, false);
  std::string msg =
      body.is_object() && body.contains("error") ? body["error"].get<std::string>() : r->body;
  std::cerr << "rockcal: HTTP " << r->status << ": " << msg;
  if (body.is_object() && body.contains("field")) std::cerr << " (field " << body["field"] << ")";
  std::cerr << "\n";
  return 1;
}

namespace {

std::string path_of(std::int64_t id, const std::string& rest = "") {
  return "/api/v1/campaigns/" + std::to_string(id) + rest;
}

}  // namespace

std::string padded(std::string text, std::size_t width) {
  std::size_t columns = 0;
  for (unsigned char ch : text) columns += (ch & 0xC0) != 0x80;
  if (columns < width) text.append(width - columns, ' ');
  return text;
}

std::string status_line(const json& c) {
  const json& p = c["progress"];
  std::ostringstream out;
  out << "campaign " << c["id"] << " " << c["state"].get<std::string>() << " "
      << progress_bar(p["fraction"].get<double>(), 30) << " " << p["succeeded"] << "/" << p["total"]
      << " done";
  if (p["cached"].get<std::int64_t>() > 0) out << " (" << p["cached"] << " cached)";
  out << ", " << p["running"] << " running, " << p["queued"] << " queued";
  if (p["failed"].get<std::int64_t>() > 0) out << ", " << p["failed"] << " failed";
  if (p["cancelled"].get<std::int64_t>() > 0) out << ", " << p["cancelled"] << " cancelled";
  if (!p["eta_seconds"].is_null() &&
      p["queued"].get<std::int64_t>() + p["running"].get<std::int64_t>() > 0) {
    out << ", ETA " << duration_text(p["eta_seconds"].get<double>());
  }
  return out.str();
}

namespace {

bool finished(const std::string& state) {
  return state == "succeeded" || state == "failed" || state == "cancelled";
}

// `line` cut to the terminal's width: a redrawn line that wraps cannot be erased by \r.
std::string fitted(const std::string& line, int fd) {
  winsize w{};
  if (ioctl(fd, TIOCGWINSZ, &w) != 0) return line;
  const std::size_t width = w.ws_col > 1 ? w.ws_col - 1 : 0;
  return width > 0 && line.size() > width ? line.substr(0, width) : line;
}

}  // namespace

std::string progress_bar(double fraction, int width) {
  fraction = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0);
  int filled = static_cast<int>(std::lround(fraction * width));
  return "[" + std::string(filled, '#') + std::string(width - filled, '.') + "] " +
         std::to_string(static_cast<int>(std::lround(fraction * 100))) + "%";
}

int client_submit(const ClientOptions& o, const std::string& file) {
  std::ostringstream body;
  if (file == "-") {
    body << std::cin.rdbuf();
  } else {
    std::ifstream in(file);
    if (!in) {
      std::cerr << "rockcal: cannot read " << file << "\n";
      return 2;
    }
    body << in.rdbuf();
  }
  Http http(o);
  auto r = http.client.Post("/api/v1/campaigns", http.headers, body.str(), "application/json");
  if (!r || r->status != 201) return http.report(r);
  std::cout << json::parse(r->body)["id"] << "\n";
  return 0;
}

std::optional<json> watch_campaign(const CampaignFetch& fetch, bool wait, int progress_fd) {
  std::ostream& progress = progress_fd == STDERR_FILENO ? std::cerr : std::cout;
  const bool tty = isatty(progress_fd);
  LinePacer pacer(std::chrono::seconds(5));
  bool drawn = false;  // a \r-redrawn line is on the terminal
  while (true) {
    std::optional<json> c = fetch();
    if (!c) {
      if (drawn) progress << "\n";
      return std::nullopt;
    }
    if (!wait || finished((*c)["state"].get<std::string>())) {
      if (drawn) progress << "\r\033[K" << std::flush;
      return c;
    }
    const std::string line = progress_line(*c);
    if (tty) {
      progress << "\r\033[K" << fitted(line, progress_fd) << std::flush;
      drawn = true;
    } else if (pacer.due(line, LinePacer::Clock::now())) {
      progress << line << std::endl;
    }
    std::this_thread::sleep_for(std::chrono::seconds(1));
  }
}

std::optional<json> Http::watch(std::int64_t id, bool wait, int progress_fd, int& exit_code) {
  return watch_campaign(
      [&]() -> std::optional<json> {
        auto r = client.Get(path_of(id), headers);
        if (!r || r->status != 200) {
          exit_code = report(r);
          return std::nullopt;
        }
        return json::parse(r->body);
      },
      wait, progress_fd);
}

int client_status(const ClientOptions& o, std::int64_t id, bool wait, bool as_json) {
  Http http(o);
  // With --json, stdout carries the campaign object alone; a --wait shows its progress on stderr.
  int exit_code = 0;
  const auto c = http.watch(id, wait, as_json ? STDERR_FILENO : STDOUT_FILENO, exit_code);
  if (!c) return exit_code;
  if (as_json) {
    std::cout << c->dump(2) << std::endl;
  } else {
    std::cout << progress_line(*c) << "\n";
    if (finished((*c)["state"].get<std::string>())) std::cout << "\n" << summary_text(*c);
    std::cout << std::flush;
  }
  return (*c)["state"] == "succeeded" || !wait ? 0 : 1;
}

namespace {

// "52 ± 0.707" (mean ± standard error), "52" for one value, "-" for none.
std::string mean_se(const json& stats) {
  if (!stats.is_object() || !stats["mean"].is_number()) return "-";
  char buffer[64];
  if (stats["se"].is_number()) {
    std::snprintf(buffer, sizeof buffer, "%.6g ± %.3g", stats["mean"].get<double>(),
                  stats["se"].get<double>());
  } else {
    std::snprintf(buffer, sizeof buffer, "%.6g", stats["mean"].get<double>());
  }
  return buffer;
}

std::string first_line(const std::string& text) {
  return text.substr(0, text.find('\n'));
}

}  // namespace

std::string results_text(const json& body) {
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line, "%-8s %10s %10s %3s %6s  ", "test", "fr0 (N)", "fs0 (N)", "n",
                "failed");
  out += line + padded("peak_load (N, mean ± se)", 26) + padded("strength (Pa, mean ± se)", 26) +
         "youngs_modulus (Pa, mean ± se)\n";
  std::string failures;
  for (const json& p : body.value("points", json::array())) {
    std::snprintf(line, sizeof line, "%-8s %10.5g %10.5g %3d %6d  ",
                  p["test"].get<std::string>().c_str(), p["fr0"].get<double>(),
                  p["fs0"].get<double>(), p["peak_load"]["n"].get<int>(), p["failed"].get<int>());
    out += line + padded(mean_se(p["peak_load"]), 26) + padded(mean_se(p["strength"]), 26) +
           mean_se(p["modulus"]) + "\n";
    for (const json& r : p["realisations"]) {
      if (!r["error"].is_string()) continue;
      std::snprintf(
          line, sizeof line,
          "  %s %.5g/%.5g seed %llu (job %lld): ", p["test"].get<std::string>().c_str(),
          p["fr0"].get<double>(), p["fs0"].get<double>(),
          static_cast<unsigned long long>(r["seed"].get<std::uint64_t>()),
          r["job_id"].is_number() ? static_cast<long long>(r["job_id"].get<std::int64_t>()) : -1LL);
      failures += line + first_line(r["error"].get<std::string>()) + "\n";
    }
  }
  if (!failures.empty()) out += "runs without values (left out of the statistics):\n" + failures;
  return out;
}

int client_results(const ClientOptions& o, std::int64_t id, bool csv) {
  Http http(o);
  auto r = http.client.Get(path_of(id, csv ? "/results?format=csv" : "/results"), http.headers);
  if (!r || r->status != 200) return http.report(r);
  if (csv) {
    std::cout << r->body;
    return 0;
  }
  std::cout << results_text(json::parse(r->body));
  return 0;
}

int client_cancel(const ClientOptions& o, std::int64_t id) {
  Http http(o);
  auto r = http.client.Delete(path_of(id), http.headers);
  if (!r || r->status != 200) return http.report(r);
  std::cout << status_line(json::parse(r->body)) << "\n";
  return 0;
}

int client_list(const ClientOptions& o) {
  Http http(o);
  auto r = http.client.Get("/api/v1/campaigns?limit=100", http.headers);
  if (!r || r->status != 200) return http.report(r);
  json body = json::parse(r->body);  // kept alive: the loop iterates one of its members
  for (const auto& c : body["campaigns"]) {
    std::cout << status_line(c) << "  " << c["kind"].get<std::string>() << " \""
              << c["name"].get<std::string>() << "\"\n";
  }
  return 0;
}

}  // namespace rockcal::api
