// Ensembles and runs without a peak through the service and its HTTP API, on the fake engine whose
// results are a formula of the seed s (peak fr0 + s - 1, strength fs0 + 2 (s - 1), modulus
// 1000 + 10 (s - 1)), so every statistic is known exactly: the results' points carry each
// realisation and mean, sd, se and n; a run without a peak is a failed job with its reason, left
// out and counted; the job cache answers realisations run before.
#include <cmath>
#include <filesystem>

#include "api_server_fixture.hpp"

namespace rockcal::test {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;

constexpr const char* kNoPeak =
    "no peak: the load fell on a loose particle with no bond broken (fake)";

json ensemble_sweep(std::vector<std::pair<double, double>> points, int realisations) {
  json r = sweep_request({"uct"}, {1}, {1});
  r.erase("grid");
  r["job"]["sample"]["packing"] = "random";
  r["points"] = json::array();
  for (auto [a, b] : points) r["points"].push_back({a, b});
  r["realisations"] = realisations;
  return r;
}

struct Ensembles : ApiServerFixture {
  std::int64_t submit(const json& request) {
    auto c = client();
    auto r = c.Post("/api/v1/campaigns", request.dump(), "application/json");
    EXPECT_TRUE(r);
    EXPECT_EQ(r->status, 201) << r->body;
    return json::parse(r->body)["id"].get<std::int64_t>();
  }
  json results(std::int64_t id) {
    auto c = client();
    json done = wait_campaign(c, id, 60s);
    EXPECT_TRUE(done["state"] == "succeeded" || done["state"] == "failed") << done.dump();
    return get_json(c, "/api/v1/campaigns/" + std::to_string(id) + "/results");
  }
  std::size_t job_dirs() {
    auto it = std::filesystem::directory_iterator(service->jobs_dir());
    return std::size_t(std::distance(it, std::filesystem::directory_iterator()));
  }
};

TEST_F(Ensembles, PointsCarryEveryRealisationAndExactStatistics) {
  start();
  const std::int64_t id = submit(ensemble_sweep({{50, 60}, {67, 60}}, 5));
  const json body = results(id);
  ASSERT_EQ(body["results"].size(), 10u);
  ASSERT_EQ(body["points"].size(), 2u);

  const json& p = body["points"][0];
  EXPECT_EQ(p["test"], "uct");
  EXPECT_EQ(p["fr0"], 50.0);
  EXPECT_EQ(p["fs0"], 60.0);
  ASSERT_EQ(p["realisations"].size(), 5u);
  for (std::uint64_t k = 0; k < 5; ++k) {
    const json& r = p["realisations"][k];
    EXPECT_EQ(r["seed"], k + 1);
    EXPECT_EQ(r["state"], "succeeded");
    EXPECT_EQ(r["peak_load_n"], 50.0 + double(k));
    EXPECT_EQ(r["strength_pa"], 60.0 + 2.0 * double(k));
    EXPECT_EQ(r["youngs_modulus_pa"], 1000.0 + 10.0 * double(k));
    EXPECT_EQ(r["error"], nullptr);
  }
  EXPECT_EQ(p["peak_load"]["n"], 5);
  EXPECT_EQ(p["peak_load"]["mean"], 52.0);
  EXPECT_EQ(p["peak_load"]["sd"], std::sqrt(2.5));
  EXPECT_DOUBLE_EQ(p["peak_load"]["se"].get<double>(), std::sqrt(0.5));
  EXPECT_EQ(p["strength"]["mean"], 64.0);
  EXPECT_EQ(p["strength"]["sd"], std::sqrt(10.0));
  EXPECT_DOUBLE_EQ(p["strength"]["se"].get<double>(), std::sqrt(2.0));
  EXPECT_EQ(p["modulus"]["mean"], 1020.0);
  EXPECT_EQ(p["modulus"]["sd"], std::sqrt(250.0));
  EXPECT_DOUBLE_EQ(p["modulus"]["se"].get<double>(), std::sqrt(50.0));
  EXPECT_EQ(p["failed"], 0);

  // fr0 67: the even seeds end without a peak. They are listed with their reason, counted, and
  // left out: the statistics are those of seeds 1, 3 and 5 (peaks 67, 69, 71).
  const json& q = body["points"][1];
  EXPECT_EQ(q["failed"], 2);
  EXPECT_EQ(q["peak_load"]["n"], 3);
  EXPECT_EQ(q["peak_load"]["mean"], 69.0);
  EXPECT_EQ(q["peak_load"]["sd"], 2.0);
  EXPECT_DOUBLE_EQ(q["peak_load"]["se"].get<double>(), 2.0 / std::sqrt(3.0));
  for (int k : {1, 3}) {
    const json& r = q["realisations"][k];
    EXPECT_EQ(r["state"], "failed");
    EXPECT_EQ(r["error"], kNoPeak);
    EXPECT_EQ(r["peak_load_n"], nullptr) << "the largest load of a run without a peak is no value";
  }
  // The per-job rows say the same.
  for (const json& row : body["results"]) {
    if (row["fr0"] == 67.0 && row["seed"].get<int>() % 2 == 0) {
      EXPECT_EQ(row["state"], "failed");
      EXPECT_EQ(row["error"], kNoPeak);
      EXPECT_EQ(row["peak_load"], nullptr);
    }
  }
  auto c = client();
  const json campaign = get_json(c, "/api/v1/campaigns/" + std::to_string(id));
  EXPECT_EQ(campaign["progress"]["failed"], 2);
}

TEST_F(Ensembles, ALargerEnsembleRunsOnlyTheNewRealisations) {
  start();
  const std::int64_t three = submit(ensemble_sweep({{50, 60}, {51, 60}}, 3));
  results(three);
  EXPECT_EQ(job_dirs(), 6u);
  const std::int64_t five = submit(ensemble_sweep({{50, 60}, {51, 60}}, 5));
  const json body = results(five);
  const db::StateCounts counts = service->store().counts(five);
  EXPECT_EQ(counts.total(), 10);
  EXPECT_EQ(counts.cached, 6) << "seeds 1-3 of both points come from the first campaign";
  EXPECT_EQ(job_dirs(), 6u + 4u) << "2 new runs per point";
  for (const json& p : body["points"]) {
    ASSERT_EQ(p["realisations"].size(), 5u);
    EXPECT_EQ(p["peak_load"]["n"], 5);
    EXPECT_EQ(p["peak_load"]["mean"], p["fr0"].get<double>() + 2.0);
  }
}

TEST_F(Ensembles, ARunWithoutAPeakIsAFailedJobWhoseResultStaysReadable) {
  start();
  const std::int64_t id = submit(ensemble_sweep({{61, 60}}, 1));
  const json body = results(id);
  ASSERT_EQ(body["results"].size(), 1u);
  const json& row = body["results"][0];
  EXPECT_EQ(row["state"], "failed");
  EXPECT_EQ(row["error"], kNoPeak);
  EXPECT_EQ(row["peak_load"], nullptr);
  EXPECT_EQ(body["points"][0]["peak_load"]["n"], 0);
  EXPECT_EQ(body["points"][0]["peak_load"]["mean"], nullptr);
  EXPECT_EQ(body["points"][0]["failed"], 1);

  auto c = client();
  const std::string job = "/api/v1/jobs/" + row["job_id"].dump();
  const json page = get_json(c, job);
  EXPECT_EQ(page["state"], "failed");
  EXPECT_EQ(page["attempts"], 1) << "deterministic: not retried";
  EXPECT_EQ(page["result"]["peak_reached"], false);
  EXPECT_EQ(page["result"]["peak_load"], 61.0) << "kept for inspection";
  auto curve = c.Get(job + "/curve");
  ASSERT_TRUE(curve);
  EXPECT_EQ(curve->status, 200);
  // The CSV row: no values, and why in the error column (quoted: the reason has commas).
  auto csv = c.Get("/api/v1/campaigns/" + std::to_string(id) + "/results?format=csv");
  ASSERT_TRUE(csv);
  EXPECT_EQ(csv->body.substr(csv->body.find('\n') + 1),
            "61,60,uct,,,,,,failed," + row["job_id"].dump() + ",1,\"" + kNoPeak + "\"\n");
  const json stored = get_json(c, "/api/v1/results?fr0_min=61&fr0_max=61");
  ASSERT_EQ(stored["results"].size(), 1u);
  EXPECT_EQ(stored["results"][0]["no_peak"],
            "the load fell on a loose particle with no bond broken (fake)");
  EXPECT_EQ(stored["results"][0]["peak_load"], nullptr);

  // The same job again is answered from the store: failed, with the reason, not run.
  const std::int64_t again = submit(ensemble_sweep({{61, 60}}, 1));
  const json second = results(again);
  EXPECT_EQ(second["results"][0]["state"], "failed");
  EXPECT_EQ(second["results"][0]["cached"], true);
  EXPECT_EQ(second["results"][0]["error"], kNoPeak);
  EXPECT_EQ(job_dirs(), 1u);
}

TEST_F(Ensembles, ABadCountIsRefusedAndStoresNothing) {
  start();
  auto c = client();
  json bad = ensemble_sweep({{50, 60}}, 3);
  bad["realisations"] = 0;
  auto r = c.Post("/api/v1/campaigns", bad.dump(), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(
      json::parse(r->body),
      json::parse(
          R"({"error": "realisations: must be an integer in [1, 100]", "field": "realisations"})"));
  bad["realisations"] = 2;
  bad["job"]["sample"]["packing"] = "fcc";  // aligned: one specimen under every seed
  bad["job"]["sample"]["lattice"] = "aligned";
  r = c.Post("/api/v1/campaigns", bad.dump(), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(json::parse(r->body)["field"], "realisations");
  expect_nothing_stored();
}

}  // namespace
}  // namespace rockcal::test
