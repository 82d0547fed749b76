// Lab-unit targets: the seed paper's lab case (examples/datasets/seed_paper) maps to its model
// targets by eq. 4.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "orchestrator/calibration/campaign.hpp"
#include "orchestrator/calibration/driver.hpp"
#include "synthetic.hpp"

namespace rockcal::calibration {
namespace {

using nlohmann::json;

// Rows of a seed-paper CSV ('#' comments, a header), keyed by the first column.
std::map<std::string, std::map<std::string, std::string>> read_csv(const std::string& name) {
  std::ifstream in(std::string(ROCKCAL_SEED_DATA) + "/" + name);
  EXPECT_TRUE(in.good()) << name;
  std::vector<std::string> header;
  std::map<std::string, std::map<std::string, std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    if (header.empty()) {
      header = cells;
      continue;
    }
    for (std::size_t i = 0; i < cells.size() && i < header.size(); ++i)
      rows[cells[0]][header[i]] = cells[i];
  }
  return rows;
}

double number(const std::string& s) {
  return std::stod(s);
}

// The seed's lab case as campaign targets in lab units; the model as in the paper (K_r2 = 8000,
// R2 = 1, rho2 = 1, x2/x1 = H2/H1 = 139 / 0.14705, D2 = 49).
json seed_lab_campaign(const std::string& quantity) {
  auto lab = read_csv("seed_lab_tests.csv");
  auto& uct = lab["uct"];
  auto& btt = lab["btt"];
  const double d = number(uct["diameter_m"]);
  const double h = number(uct["height_m"]);
  json targets = {
      {"units", "lab"},
      {"uct", {{"peak_load", number(uct["max_load_n"])}}},
      {"btt", {{"peak_load", number(btt["max_load_n"])}}},
      {"lab",
       {{"specimen", {{"diameter", d}, {"height", h}, {"thickness", 0.5 * d}}},
        {"material",
         {{"youngs_modulus", number(uct["youngs_modulus_pa"])},
          {"nu", number(uct["poisson_ratio_min"])},
          {"density", number(uct["density_kg_m3"])},
          {"grain_radius", number(uct["grain_radius_m"])}}}}},
      {"model_scale", {{"kr", 8000}, {"radius", 1}, {"density", 1}, {"length_ratio", 139 / h}}}};
  if (quantity == "strength") {
    // The same loads given as UCS = F / A and BTS = 2P / (pi D t).
    const double ucs = number(uct["max_load_n"]) / (M_PI * d * d / 4);
    const double bts = 2 * number(btt["max_load_n"]) / (M_PI * d * 0.5 * d);
    targets["uct"] = {{"strength", ucs}, {"peak_load", nullptr}};  // merge patch: null deletes
    targets["btt"] = {{"strength", bts}, {"peak_load", nullptr}};
  }
  return testing::campaign_json(
      {1, 1}, {{"targets", targets}, {"job", {{"sample", {{"diameter", 49}, {"height", 139}}}}}});
}

TEST(LabTargets, SeedLabUctMapsToThePapersModelTarget) {
  auto scaling = read_csv("seed_model_scaling.csv");
  const double f2_uct = number(scaling["F2_uct_n"]["value"]);  // 161850
  for (const char* quantity : {"peak_load", "strength"}) {
    const CalibrationCampaign c = parse_calibration_campaign(seed_lab_campaign(quantity));
    EXPECT_NEAR(c.targets.model_loads_n.uct_n / f2_uct, 1.0, 5e-4) << quantity;
    // The BTT disc (D = 54.46 mm, t = D/2) maps with the same force scale: 51.9 kN -> about 27 kN.
    EXPECT_NEAR(c.targets.model_loads_n.btt_n, 51900 * c.targets.scaling->force, 1e-6) << quantity;
    EXPECT_NEAR(c.targets.model_loads_n.btt_n, 27000, 100) << quantity;
    EXPECT_NEAR(c.targets.scaling->kr_lab_n_m, number(scaling["K_r1_N_per_m"]["value"]), 0.001e7);
  }
}

TEST(LabTargets, ReportGivesBothUnitSystems) {
  const CalibrationCampaign c = parse_calibration_campaign(seed_lab_campaign("peak_load"));
  // A model that meets the targets exactly at (64, 64) model units: 161850 and ~27000 N.
  const PeakLoads at64 = testing::power_law({64, 64});
  const PeakLoads t = c.targets.model_loads_n;
  testing::ModelEvaluator evaluator([&](const BondPoint& p) {
    const PeakLoads l = testing::power_law(p);
    return PeakLoads{l.uct_n * t.uct_n / at64.uct_n, l.btt_n * t.btt_n / at64.btt_n};
  });
  const CalibrationReport r = run_calibration(c, evaluator);
  ASSERT_EQ(r.verdict, Verdict::feasible);
  const json j = to_json(r, c);
  const json& best = j["best"];
  const double force = c.targets.scaling->force;
  EXPECT_NEAR(best["lab"]["fr0"].get<double>(), best["fr0"].get<double>() / force, 1e-9);
  EXPECT_NEAR(best["lab"]["uct"]["peak_load"].get<double>() / 311000, 1.0, 0.02);
  EXPECT_NEAR(best["lab"]["btt"]["peak_load"].get<double>() / 51900, 1.0, 0.02);
  // Lab strengths: UCS 133.5 MPa, BTS 22.3 MPa (field notes).
  EXPECT_NEAR(best["lab"]["uct"]["strength"].get<double>() / 133.5e6, 1.0, 0.025);
  EXPECT_NEAR(best["lab"]["btt"]["strength"].get<double>() / 22.3e6, 1.0, 0.025);
  EXPECT_NEAR(j["targets"]["lab"]["uct"]["peak_load"].get<double>(), 311000, 1e-6);
  EXPECT_NEAR(j["targets"]["scaling"]["lab_specimen_in_model_units"]["height"].get<double>(), 139,
              1e-9);
}

}  // namespace
}  // namespace rockcal::calibration
