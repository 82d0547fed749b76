// The dashboard's serving: the shell at every page path, every module it imports embedded and
// served with its type, nothing outside the embedded table, revalidation by ETag, and the
// examples the submit page offers.
#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <sstream>

#include "api_server_fixture.hpp"

namespace rockcal::test {
namespace {

using nlohmann::json;

struct Dashboard : ApiServerFixture {};

// "/ui/pages/../dom.js" -> "/ui/dom.js"
std::string normalise(const std::string& path) {
  std::vector<std::string> parts;
  std::size_t at = 0;
  while (at <= path.size()) {
    std::size_t next = path.find('/', at);
    if (next == std::string::npos) next = path.size();
    std::string part = path.substr(at, next - at);
    if (part == "..") {
      if (!parts.empty()) parts.pop_back();
    } else if (!part.empty() && part != ".") {
      parts.push_back(part);
    }
    at = next + 1;
  }
  std::string out;
  for (const auto& p : parts) out += "/" + p;
  return out;
}

// The targets of `import ... from './x.js'` lines (the dashboard's modules import one per line).
std::vector<std::string> relative_imports(const std::string& source) {
  std::vector<std::string> out;
  std::istringstream in(source);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("import ", 0) != 0 && line.rfind("export ", 0) != 0) continue;
    auto from = line.find(" from '.");
    if (from == std::string::npos) continue;
    auto start = from + 7;
    auto end = line.find('\'', start);
    if (end != std::string::npos) out.push_back(line.substr(start, end - start));
  }
  return out;
}

TEST_F(Dashboard, EveryPagePathServesTheShell) {
  start();
  auto c = client();
  for (const char* path : {"/", "/campaigns", "/campaigns/7", "/jobs/3", "/submit"}) {
    auto r = c.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 200) << path;
    EXPECT_EQ(r->get_header_value("Content-Type"), "text/html; charset=utf-8") << path;
    EXPECT_NE(r->body.find(R"(<script type="module" src="/ui/app.js">)"), std::string::npos)
        << path;
    EXPECT_NE(r->get_header_value("Content-Security-Policy").find("script-src 'self'"),
              std::string::npos);
  }
  // The API's own 404 shape for everything else.
  for (const char* path : {"/campaigns/7/x", "/jobs", "/nope", "/ui/missing.js"}) {
    auto r = c.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 404) << path;
    EXPECT_TRUE(json::parse(r->body, nullptr, false).contains("error")) << path << ": " << r->body;
  }
}

// Follows the shell's stylesheet and script, then every static import, as the browser would.
TEST_F(Dashboard, EveryModuleTheShellLoadsIsServedWithItsType) {
  start();
  auto c = client();
  std::set<std::string> seen;
  std::vector<std::string> todo;
  auto shell = c.Get("/");
  ASSERT_TRUE(shell);
  std::regex asset(R"re((?:src|href)="(/ui/[^"]+)")re");
  for (std::sregex_iterator it(shell->body.begin(), shell->body.end(), asset), end; it != end; ++it)
    todo.push_back((*it)[1]);
  ASSERT_EQ(todo.size(), 2u);
  while (!todo.empty()) {
    const std::string path = todo.back();
    todo.pop_back();
    if (!seen.insert(path).second) continue;
    auto r = c.Get(path);
    ASSERT_TRUE(r) << path;
    ASSERT_EQ(r->status, 200) << path << " (imported but not embedded?)";
    const bool js = path.ends_with(".js");
    EXPECT_EQ(r->get_header_value("Content-Type"),
              js ? "text/javascript; charset=utf-8" : "text/css; charset=utf-8")
        << path;
    EXPECT_EQ(r->get_header_value("X-Content-Type-Options"), "nosniff");
    if (!js) continue;
    const std::string dir = path.substr(0, path.rfind('/') + 1);
    for (const std::string& target : relative_imports(r->body))
      todo.push_back(normalise(dir + target));
  }
  // The shell, its stylesheet, the app and its pages, the plots: a broken import shows up above.
  EXPECT_GE(seen.size(), 20u);
  EXPECT_TRUE(seen.count("/ui/plot/heat_map.js"));
  EXPECT_TRUE(seen.count("/ui/pages/submit.js"));
}

TEST_F(Dashboard, NothingOutsideTheEmbeddedFilesIsServed) {
  start();
  auto c = client();
  for (const char* path : {"/ui/../CMakeLists.txt", "/ui/%2e%2e/server.cpp", "/ui/dashboard.cpp",
                           "/ui//etc/passwd", "/ui/examples/../../README.md"}) {
    auto r = c.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 404) << path;
  }
}

TEST_F(Dashboard, AnUnchangedFileIsRevalidatedNotResent) {
  start();
  auto c = client();
  auto first = c.Get("/ui/app.js");
  ASSERT_TRUE(first);
  const std::string etag = first->get_header_value("ETag");
  ASSERT_FALSE(etag.empty());
  EXPECT_EQ(first->get_header_value("Cache-Control"), "no-cache");
  auto again = c.Get("/ui/app.js", {{"If-None-Match", etag}});
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 304);
  EXPECT_TRUE(again->body.empty());
  auto other = c.Get("/ui/dom.js", {{"If-None-Match", etag}});
  ASSERT_TRUE(other);
  EXPECT_EQ(other->status, 200);
}

// The submit page's starting points are the repository's campaign examples, served as they are.
TEST_F(Dashboard, TheExamplesIndexListsTheCampaignExamples) {
  start();
  auto c = client();
  auto r = c.Get("/ui/examples/index.json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200);
  json index = json::parse(r->body);
  std::set<std::string> files;
  for (const json& e : index) {
    files.insert(e["file"]);
    auto f = c.Get("/ui/" + e["file"].get<std::string>());
    ASSERT_TRUE(f);
    ASSERT_EQ(f->status, 200) << e.dump();
    json request = json::parse(f->body);
    EXPECT_EQ(request["kind"], e["kind"]);
    EXPECT_EQ(request["name"], e["name"]);
    if (request.contains("dataset_file")) {
      auto d = c.Get("/ui/examples/" + request["dataset_file"].get<std::string>());
      ASSERT_TRUE(d);
      EXPECT_EQ(d->status, 200) << request["dataset_file"];
    }
  }
  EXPECT_TRUE(files.count("examples/calibrate_seed_lab.json"));
  EXPECT_TRUE(files.count("examples/diagnose_seed_lab.json"));
  EXPECT_TRUE(files.count("examples/sweep_small.json"));
  EXPECT_FALSE(files.count("examples/uct_small.json"));  // a job spec, not a campaign
}

}  // namespace
}  // namespace rockcal::test
