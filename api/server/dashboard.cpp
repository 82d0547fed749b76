#include "api/server/dashboard.hpp"

#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>

#include <nlohmann/json.hpp>

#include "api/server/dashboard_assets.hpp"
#include "api/server/http_util.hpp"

namespace rockcal::api {

namespace {

// The page runs only its own files: no inline script, no other origin.
constexpr const char* kPolicy =
    "default-src 'self'; img-src 'self' data:; style-src 'self'; script-src 'self'; "
    "connect-src 'self'; frame-ancestors 'none'; base-uri 'none'; form-action 'none'";

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

// FNV-1a of the body: a validator that changes with the build's files.
std::string etag_of(std::string_view body) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : body) h = (h ^ c) * 1099511628211ull;
  char buf[24];
  std::snprintf(buf, sizeof buf, "\"%016llx\"", static_cast<unsigned long long>(h));
  return buf;
}

struct Served {
  std::string_view body;
  std::string content_type;
  std::string etag;
};

// Everything the dashboard serves, built once; the handlers only look up.
struct Catalogue {
  std::string examples_index;  // owns the body of "examples/index.json"
  std::map<std::string, Served, std::less<>> files;

  void add(std::string_view path, std::string_view body) {
    files.emplace(std::string(path), Served{body, content_type_of(path), etag_of(body)});
  }
};

// The campaign requests among the embedded examples (top-level examples/*.json with a "kind"):
// the submit page's list of starting points.
std::string examples_index(std::span<const EmbeddedFile> files) {
  const std::string_view dir = "examples/";
  nlohmann::json list = nlohmann::json::array();
  for (const EmbeddedFile& f : files) {
    if (f.path.substr(0, dir.size()) != dir || !ends_with(f.path, ".json")) continue;
    if (f.path.find('/', dir.size()) != std::string_view::npos) continue;  // datasets/
    nlohmann::json j = nlohmann::json::parse(f.body, nullptr, false);
    if (!j.is_object() || !j.contains("kind") || !j["kind"].is_string()) continue;
    list.push_back({{"file", std::string(f.path)},
                    {"kind", j["kind"]},
                    {"name", j.value("name", std::string(f.path))}});
  }
  return list.dump();
}

// Answers with the file, or 304 when the browser already holds this version. no-cache: the
// browser revalidates every time, so a new build is never hidden behind a stale copy.
void send_file(const Served& f, const httplib::Request& req, httplib::Response& res) {
  res.set_header("Cache-Control", "no-cache");
  res.set_header("ETag", f.etag);
  res.set_header("X-Content-Type-Options", "nosniff");
  if (req.get_header_value("If-None-Match") == f.etag) {
    res.status = 304;
    return;
  }
  res.set_content(f.body.data(), f.body.size(), f.content_type);
}

}  // namespace

std::string content_type_of(std::string_view path) {
  if (ends_with(path, ".html")) return "text/html; charset=utf-8";
  if (ends_with(path, ".js")) return "text/javascript; charset=utf-8";
  if (ends_with(path, ".css")) return "text/css; charset=utf-8";
  if (ends_with(path, ".json")) return "application/json";
  if (ends_with(path, ".csv")) return "text/csv; charset=utf-8";
  return "application/octet-stream";
}

void mount_dashboard(httplib::Server& server) {
  auto catalogue = std::make_shared<Catalogue>();
  for (const EmbeddedFile& f : dashboard_files()) catalogue->add(f.path, f.body);
  catalogue->examples_index = examples_index(dashboard_files());
  catalogue->add("examples/index.json", catalogue->examples_index);
  auto shell = catalogue->files.find(std::string_view("index.html"));
  if (shell == catalogue->files.end()) throw std::logic_error("the dashboard has no index.html");

  server.Get("/ui/(.+)", [catalogue](const httplib::Request& req, httplib::Response& res) {
    // An exact match in the embedded table: no request text ever reaches the file system.
    const std::string name = req.matches[1].str();
    auto it = catalogue->files.find(name);
    if (it == catalogue->files.end()) {
      send_error(res, 404, "no dashboard file " + name);
      return;
    }
    send_file(it->second, req, res);
  });
  for (const char* page : kDashboardPages) {
    server.Get(page, [catalogue, shell](const httplib::Request& req, httplib::Response& res) {
      res.set_header("Content-Security-Policy", kPolicy);
      res.set_header("Referrer-Policy", "same-origin");
      send_file(shell->second, req, res);
    });
  }
}

}  // namespace rockcal::api
