// api/openapi.yaml documents exactly the routes the server registers, and each one is served.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>

#include "api_server_fixture.hpp"

namespace rockcal::test {
namespace {

using Route = std::pair<std::string, std::string>;  // METHOD, path template

// The `paths:` section: path keys at two spaces, operations at four.
std::set<Route> documented_routes() {
  std::ifstream in(openapi_file());
  EXPECT_TRUE(in) << openapi_file();
  std::set<Route> out;
  std::regex path_line(R"(^  (/[^:\s]*):\s*$)");
  std::regex op_line(R"(^    (get|post|put|patch|delete|head|options):)");
  std::string line, current;
  bool in_paths = false;
  while (std::getline(in, line)) {
    std::smatch m;
    if (!line.empty() && line[0] != ' ') in_paths = line.rfind("paths:", 0) == 0;
    if (!in_paths) continue;
    if (std::regex_match(line, m, path_line)) {
      current = m[1];
    } else if (std::regex_search(line, m, op_line) && !current.empty()) {
      std::string method = m[1];
      for (auto& ch : method) ch = static_cast<char>(std::toupper(ch));
      out.insert({method, current});
    }
  }
  return out;
}

struct OpenApi : ApiServerFixture {};

TEST_F(OpenApi, DocumentsExactlyTheRegisteredRoutes) {
  start();
  std::set<Route> registered;
  for (const auto& r : server->routes()) registered.insert({r.method, r.path});
  auto documented = documented_routes();
  EXPECT_GE(documented.size(), 10u);
  for (const auto& r : registered) {
    EXPECT_TRUE(documented.count(r)) << r.first << " " << r.second << " is not in openapi.yaml";
  }
  for (const auto& r : documented) {
    EXPECT_TRUE(registered.count(r)) << r.first << " " << r.second << " is documented, not served";
  }
}

TEST_F(OpenApi, EveryDocumentedRouteIsRouted) {
  start();
  auto c = client();
  for (const auto& [method, path] : documented_routes()) {
    std::string concrete = std::regex_replace(path, std::regex(R"(\{[^}]+\})"), "1");
    httplib::Result r = method == "GET"    ? c.Get(concrete)
                        : method == "POST" ? c.Post(concrete, "{}", "application/json")
                                           : c.Delete(concrete);
    ASSERT_TRUE(r) << method << " " << concrete;
    EXPECT_EQ(r->body.find("no such route"), std::string::npos) << method << " " << concrete;
    EXPECT_LT(r->status, 500) << method << " " << concrete << ": " << r->body;
  }
}

}  // namespace
}  // namespace rockcal::test
