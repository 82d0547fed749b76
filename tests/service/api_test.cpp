// The REST API over real HTTP: bad input, auth, path safety, and the happy path (fake engine).
#include <gtest/gtest.h>

#include <fstream>

#include "api_server_fixture.hpp"

namespace rockcal::test {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

struct Api : ApiServerFixture {};

// POSTs `body`; checks the status, that the reply is our JSON error shape, and returns the field.
std::string post_expecting(httplib::Client& c, const std::string& body, int status) {
  auto r = c.Post("/api/v1/campaigns", body, "application/json");
  if (!r) {
    ADD_FAILURE() << "transport error " << httplib::to_string(r.error());
    return "";
  }
  EXPECT_EQ(r->status, status) << body.substr(0, 200) << " -> " << r->body;
  json j = json::parse(r->body, nullptr, false);
  EXPECT_TRUE(j.is_object() && j.contains("error") && j["error"].is_string() &&
              !j["error"].get<std::string>().empty())
      << r->body;
  return j.is_object() ? j.value("field", "") : "";
}

TEST_F(Api, BadRequestsGetA4xxNamingTheFieldAndStoreNothing) {
  start();
  auto c = client();
  json good = sweep_request({"uct", "btt"}, {50, 80}, {60, 90});
  auto with = [&](const std::function<void(json&)>& edit) {
    json r = good;
    edit(r);
    return r.dump();
  };
  EXPECT_EQ(post_expecting(c, "{\"kind\": \"sweep\", ", 400), "(body)");
  EXPECT_EQ(post_expecting(c, "", 400), "(body)");
  EXPECT_EQ(post_expecting(c, "[1, 2]", 400), "(body)");
  std::string nan_body = good.dump();
  nan_body.replace(nan_body.find("[50.0,80.0]"), 11, "[NaN, 80]");
  EXPECT_EQ(post_expecting(c, nan_body, 400), "(body)") << "NaN is not JSON";
  std::string inf_body = good.dump();
  inf_body.replace(inf_body.find("[50.0,80.0]"), 11, "[1e999, 80]");
  EXPECT_EQ(post_expecting(c, inf_body, 400), "(body)") << "a number that overflows a double";
  EXPECT_EQ(post_expecting(c, with([](json& r) { r.erase("kind"); }), 400), "kind");
  EXPECT_EQ(post_expecting(c, with([](json& r) { r["kind"] = "bogus"; }), 400), "kind");
  EXPECT_EQ(post_expecting(c, with([](json& r) { r["kind"] = 3; }), 400), "kind");
  EXPECT_EQ(post_expecting(c, with([](json& r) { r["tests"] = "uct"; }), 400), "tests");
  EXPECT_EQ(post_expecting(c, with([](json& r) { r["grid"]["fr0"] = "50"; }), 400), "grid.fr0");
  EXPECT_EQ(post_expecting(c, with([](json& r) {
                             r["grid"]["fs0"] = {1, true};
                           }),
                           400),
            "grid.fs0[1]");
  EXPECT_EQ(post_expecting(c, with([](json& r) { r["priority"] = 1; }), 400), "priority");
  EXPECT_EQ(post_expecting(c, with([](json& r) { r["job"]["sample"]["colour"] = 1; }), 400),
            "job.sample.colour");
  EXPECT_EQ(post_expecting(c, with([](json& r) { r["job"]["material"]["kr"] = "stiff"; }), 400),
            "job.material.kr");
  EXPECT_EQ(post_expecting(c, with([](json& r) { r["job"]["sample"]["radius"] = 0; }), 400),
            "job.sample.radius");
  // Enormous grids are refused by size, not expanded (cap 100 jobs here).
  std::vector<double> many(5000, 1.0);
  auto field = post_expecting(c, with([&](json& r) {
                                r["grid"] = {{"fr0", many}, {"fs0", many}};
                              }),
                              400);
  EXPECT_EQ(field.rfind("grid", 0), 0u) << field;
  EXPECT_EQ(post_expecting(
                c, with([&](json& r) { r["grid"]["fr0"] = std::vector<double>(30, 2.0); }), 400),
            "grid");  // 30 x 2 points x 2 tests = 120 > 100
  // A body over the limit (64 KiB here) is refused before it is parsed.
  std::string huge = good.dump();
  huge.insert(huge.size() - 1, ", \"pad\": \"" + std::string(200 * 1024, 'x') + "\"");
  auto r = c.Post("/api/v1/campaigns", huge, "application/json");
  ASSERT_TRUE(r) << httplib::to_string(r.error());
  EXPECT_EQ(r->status, 413);
  EXPECT_NE(r->body.find("too large"), std::string::npos) << r->body;
  expect_nothing_stored();
}

TEST_F(Api, UnknownRoutesBadIdsAndBadQueriesAreJson4xx) {
  start();
  auto c = client();
  struct Case {
    std::string path;
    int status;
    std::string field;
  };
  for (const auto& k : std::vector<Case>{{"/nope", 404, ""},
                                         {"/api/v2/campaigns", 404, ""},
                                         {"/api/v1/campaigns/abc", 400, "id"},
                                         {"/api/v1/campaigns/-1", 400, "id"},
                                         {"/api/v1/campaigns/99999999999999999999", 400, "id"},
                                         {"/api/v1/campaigns/7", 404, ""},
                                         {"/api/v1/jobs/7", 404, ""},
                                         {"/api/v1/jobs/7/log", 404, ""},
                                         {"/api/v1/campaigns?limit=0", 400, "limit"},
                                         {"/api/v1/campaigns?limit=ten", 400, "limit"},
                                         {"/api/v1/results?fr0_min=abc", 400, "fr0_min"},
                                         {"/api/v1/results?fr0_min=nan", 400, "fr0_min"},
                                         {"/api/v1/results?test=shear", 400, "test"},
                                         {"/api/v1/results?sort=fr0", 400, "sort"}}) {
    auto r = c.Get(k.path);
    ASSERT_TRUE(r) << k.path;
    EXPECT_EQ(r->status, k.status) << k.path << " -> " << r->body;
    json j = json::parse(r->body, nullptr, false);
    ASSERT_TRUE(j.is_object() && j.contains("error")) << k.path << " -> " << r->body;
    EXPECT_EQ(j.value("field", ""), k.field) << k.path;
  }
  auto r = c.Delete("/api/v1/campaigns/5");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
  expect_nothing_stored();
}

TEST_F(Api, NothingInARequestNamesAFileOutsideTheDataDirectory) {
  start();
  std::ofstream(dir.path() / "secret.txt") << "TOP-SECRET\n";
  auto c = client();
  // Create one job so that job 1 exists and has a log.
  auto created =
      c.Post("/api/v1/campaigns", sweep_request({"uct"}, {31}, {1}).dump(), "application/json");
  ASSERT_TRUE(created && created->status == 201);
  for (const char* path :
       {"/api/v1/jobs/..%2F..%2Fsecret.txt/log", "/api/v1/jobs/1/../../../secret.txt",
        "/api/v1/jobs/%2e%2e/log", "/api/v1/jobs/1%2F..%2F..%2Fsecret.txt/log",
        "/api/v1/jobs/..%2F..%2F..%2Fsecret.txt/curve", "/api/v1/jobs/1.0/log",
        "/api/v1/jobs/0x1/log", "/../secret.txt", "/api/v1/jobs/+1/log"}) {
    auto r = c.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_GE(r->status, 400) << path;
    EXPECT_LT(r->status, 500) << path;
    EXPECT_EQ(r->body.find("TOP-SECRET"), std::string::npos) << path;
  }
}

TEST_F(Api, TokenGuardsEveryMutatingRoute) {
  start(std::string("s3cret-token"));
  auto c = client();
  std::string body = sweep_request({"uct"}, {31}, {1}).dump();
  for (const httplib::Headers& h :
       {httplib::Headers{}, httplib::Headers{{"Authorization", "Bearer wrong-token!"}},
        httplib::Headers{{"Authorization", "s3cret-token"}},
        httplib::Headers{{"Authorization", "Bearer s3cret-tokenX"}}}) {
    auto r = c.Post("/api/v1/campaigns", h, body, "application/json");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 401) << r->body;
    EXPECT_EQ(json::parse(r->body)["field"], "Authorization");
    auto d = c.Delete("/api/v1/campaigns/1", h);
    ASSERT_TRUE(d);
    EXPECT_EQ(d->status, 401);
  }
  expect_nothing_stored();
  httplib::Headers good = {{"Authorization", "Bearer s3cret-token"}};
  auto r = c.Post("/api/v1/campaigns", good, body, "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 201) << r->body;
  // Reads need no token.
  auto g = c.Get("/api/v1/campaigns/1");
  ASSERT_TRUE(g);
  EXPECT_EQ(g->status, 200);
  // The scheme's name is case-insensitive.
  auto lower = c.Delete("/api/v1/campaigns/1", {{"Authorization", "bearer s3cret-token"}});
  ASSERT_TRUE(lower);
  EXPECT_NE(lower->status, 401) << lower->body;
}

TEST_F(Api, ProtectedReadsNeedTheTokenButHealthAndTheDashboardDoNot) {
  start(std::string("s3cret-token"), 100, [](api::ServerConfig& sc) { sc.protect_reads = true; });
  auto c = client();
  for (const std::string path : {"/api/v1/campaigns", "/api/v1/campaigns/1", "/api/v1/results",
                                 "/api/v1/jobs/1/log", "/metrics"}) {
    auto r = c.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 401) << path;
    EXPECT_EQ(json::parse(r->body),
              json({{"error", "missing or wrong bearer token (Authorization: Bearer <token>)"},
                    {"field", "Authorization"}}))
        << path;
  }
  for (const std::string path : {"/healthz", "/"}) {
    auto r = c.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 200) << path;
  }
  auto r = c.Get("/api/v1/campaigns", {{"Authorization", "BEARER s3cret-token"}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
}

TEST_F(Api, AKeyGivenTwiceIsRefusedNamingItAndStoresNothing) {
  start();
  auto c = client();
  std::string body = sweep_request({"uct"}, {31}, {1}).dump();
  const std::string bond = "\"bond\":{";
  body.replace(body.find(bond), bond.size(), bond + "\"fr0\":1,\"fr0\":2,");
  auto r = c.Post("/api/v1/campaigns", body, "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(json::parse(r->body),
            json({{"error", "job.bond.fr0: given more than once"}, {"field", "job.bond.fr0"}}))
      << body;
  expect_nothing_stored();
}

TEST_F(Api, SweepLifecycleOverHttp) {
  start();
  auto c = client();
  auto r = c.Post("/api/v1/campaigns", sweep_request({"uct", "btt"}, {31, 37}, {1}).dump(),
                  "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  auto id = json::parse(r->body)["id"].get<std::int64_t>();
  EXPECT_EQ(r->get_header_value("Location"), "/api/v1/campaigns/" + std::to_string(id));
  json done = wait_campaign(c, id, 30s);
  ASSERT_EQ(done["state"], "succeeded") << done.dump();
  EXPECT_EQ(done["progress"]["succeeded"], 4);
  EXPECT_EQ(done["progress"]["fraction"], 1.0);

  json results = get_json(c, "/api/v1/campaigns/" + std::to_string(id) + "/results");
  ASSERT_EQ(results["results"].size(), 4u);
  for (const auto& row : results["results"]) {
    EXPECT_EQ(row["state"], "succeeded");
    EXPECT_EQ(row["peak_load"], row["fr0"]);  // the fake engine echoes fr0 as the peak
  }
  auto csv = c.Get("/api/v1/campaigns/" + std::to_string(id) + "/results?format=csv");
  ASSERT_TRUE(csv);
  EXPECT_EQ(csv->get_header_value("Content-Type"), "text/csv");
  EXPECT_EQ(std::count(csv->body.begin(), csv->body.end(), '\n'), 5);
  EXPECT_EQ(csv->body.rfind(
                "fr0_n,fs0_n,test,peak_load_n,strength_pa,youngs_modulus_pa,particles,wall_seconds,"
                "state",
                0),
            0u);

  std::int64_t job_id = results["results"][0]["job_id"];
  json job = get_json(c, "/api/v1/jobs/" + std::to_string(job_id));
  EXPECT_EQ(job["state"], "succeeded");
  EXPECT_EQ(job["spec"]["test"], "uct");
  EXPECT_EQ(job["result"]["particles"], 7);
  auto log = c.Get("/api/v1/jobs/" + std::to_string(job_id) + "/log");
  ASSERT_TRUE(log);
  EXPECT_NE(log->body.find("fake-rockcal-dem: done"), std::string::npos);
  auto curve = c.Get("/api/v1/jobs/" + std::to_string(job_id) + "/curve");
  ASSERT_TRUE(curve);
  EXPECT_EQ(curve->body.rfind("step,time_s,displacement_m,load_n,broken_bonds", 0), 0u);

  json filtered = get_json(c, "/api/v1/results?test=btt&fr0_min=35&fr0_max=40");
  ASSERT_EQ(filtered["results"].size(), 1u);
  EXPECT_EQ(filtered["results"][0]["fr0"], 37.0);

  auto cancel = c.Delete("/api/v1/campaigns/" + std::to_string(id));
  ASSERT_TRUE(cancel);
  EXPECT_EQ(cancel->status, 409);

  json list = get_json(c, "/api/v1/campaigns?limit=1");
  EXPECT_EQ(list["total"], 1);
  EXPECT_EQ(list["campaigns"][0]["id"], id);

  auto metrics = c.Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_NE(metrics->body.find("rockcal_jobs{state=\"succeeded\"} 4"), std::string::npos);
  EXPECT_NE(metrics->body.find("rockcal_queue_length 0"), std::string::npos);
  EXPECT_NE(metrics->body.find("rockcal_job_duration_seconds_count 4"), std::string::npos);
  json health = get_json(c, "/healthz");
  EXPECT_EQ(health["status"], "ok");
}

TEST_F(Api, CancelOverHttpStopsTheCampaign) {
  start();
  auto c = client();
  auto r = c.Post("/api/v1/campaigns", sweep_request({"uct"}, {17}, {1, 2, 3}).dump(),
                  "application/json");
  ASSERT_TRUE(r && r->status == 201);
  auto id = json::parse(r->body)["id"].get<std::int64_t>();
  ASSERT_TRUE(poll_until([&] { return service->store().counts(id).running > 0; }, 10s));
  auto d = c.Delete("/api/v1/campaigns/" + std::to_string(id));
  ASSERT_TRUE(d);
  EXPECT_EQ(d->status, 200) << d->body;
  EXPECT_EQ(json::parse(d->body)["state"], "cancelled");
  ASSERT_TRUE(poll_until([&] { return processes_mentioning(dir.path().string()).empty(); }, 10s));
}

}  // namespace
}  // namespace rockcal::test
