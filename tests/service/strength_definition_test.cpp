// One BTS definition everywhere: a calibration on the real engine (tiny specimens, the default
// flattened Brazilian disc) states and applies the same strength, k 2P / (pi D t) with the
// set-up's k, in the engine's result, the results API and the calibration report.
#include <gtest/gtest.h>

#include <cmath>

#include "support.hpp"

namespace rockcal::test {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

json tiny_calibration() {
  json job = tiny_job_template();
  job.erase("bond");
  return {{"kind", "calibration"},
          {"name", "strength definition"},
          {"job", job},
          {"bounds", {{"fr0", {50, 80}}, {"fs0", {50, 70}}}},
          {"targets", {{"uct", {{"peak_load", 100}}}, {"btt", {{"peak_load", 20}}}}},
          {"strategy", "direct_2d"},
          {"initial_points", 2},
          {"max_evaluations", 4},
          {"consistency_evaluations", 0},
          {"suggest", false}};
}

TEST(StrengthDefinition, EngineResultsApiAndCalibrationReportStateAndApplyTheSameBts) {
  TempDir dir;
  ServerProcess server(dir.path(),
                       {"--engine", engine_binary(), "--ranks-per-job", "1", "--workers", "2"});
  server.start();
  auto c = server.client();
  auto r = c.Post("/api/v1/campaigns", tiny_calibration().dump(), "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  const auto id = json::parse(r->body)["id"].get<std::int64_t>();
  const json done = wait_campaign(c, id, 150s);
  const json& report = done["summary"];
  ASSERT_TRUE(report["best"].is_object()) << done.dump(2) << server.stderr_text();
  const json& best = report["best"];

  // The best point's BTT job, through the results API.
  const json rows = get_json(c, "/api/v1/campaigns/" + std::to_string(id) + "/results");
  json row;
  for (const json& x : rows["results"])
    if (x["test"] == "btt" && x["fr0"] == best["fr0"] && x["fs0"] == best["fs0"]) row = x;
  ASSERT_TRUE(row.is_object()) << rows.dump(2);
  const json job = get_json(c, "/api/v1/jobs/" + row["job_id"].dump());
  const json& result = job["result"];

  // The engine's result: the default flattened disc (2 alpha = 30 degrees) and its factor, applied.
  const double k = result["btt"]["strength_factor"].get<double>();
  EXPECT_NEAR(k, 0.9131, 1e-4);
  const json definition = {{"name", "BTS"}, {"formula", "k 2P / (pi D t)"}, {"factor", k}};
  EXPECT_EQ(result["strength_definition"], definition);
  const double d = job["spec"]["sample"]["diameter"].get<double>();
  const double t = job["spec"]["sample"]["thickness"].get<double>();
  const double load = result["peak_load"].get<double>();
  const double bts = result["strength"].get<double>();
  EXPECT_NEAR(bts, k * 2 * load / (M_PI * d * t), 1e-12 * bts);

  // The results API: the same number and the same definition.
  EXPECT_EQ(row["strength"].get<double>(), bts);
  EXPECT_EQ(row["strength_definition"], definition);

  // The calibration report: one realisation, so the best BTT load is this run's, and its strength
  // the same number by the same definition.
  ASSERT_EQ(best["btt"]["n"], 1);
  EXPECT_EQ(best["btt"]["peak_load"].get<double>(), load);
  EXPECT_EQ(best["btt"]["strength"].get<double>(), bts);
  EXPECT_EQ(report["strength_definitions"]["model"]["btt"], definition);
  EXPECT_EQ(report["strength_definitions"]["model"]["uct"],
            (json{{"name", "UCS"}, {"formula", "F / A"}, {"factor", 1.0}}));
}

}  // namespace
}  // namespace rockcal::test
