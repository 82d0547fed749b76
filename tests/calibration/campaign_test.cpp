// Campaign validation: every bad spec is rejected with the offending field named.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>

#include "orchestrator/calibration/campaign.hpp"
#include "synthetic.hpp"

namespace rockcal::calibration {
namespace {

using nlohmann::json;

json lab_targets() {
  return {{"units", "lab"},
          {"uct", {{"peak_load", 311000}}},
          {"btt", {{"peak_load", 51900}}},
          {"lab",
           {{"specimen", {{"diameter", 0.05446}, {"height", 0.14705}}},
            {"material",
             {{"youngs_modulus", 12.33e9},
              {"nu", 0.2},
              {"density", 2711.6},
              {"grain_radius", 0.001}}}}},
          {"model_scale", {{"kr", 8000}, {"radius", 1}, {"density", 1}}}};
}

struct BadCase {
  const char* what;
  json overrides;  // merge patch onto a valid campaign (null deletes)
  const char* field;
};

std::string field_of(const json& overrides) {
  try {
    testing::campaign({1000, 100}, overrides);
  } catch (const orch::RequestError& e) {
    return e.field;
  }
  return "(accepted)";
}

TEST(Campaign, ValidSpecParsesWithDefaults) {
  const CalibrationCampaign c = testing::campaign({161850, 27000});
  EXPECT_EQ(c.max_evaluations, 40);
  EXPECT_DOUBLE_EQ(c.tolerance, 0.02);
  EXPECT_EQ(c.algorithm, "bobyqa");
  EXPECT_EQ(c.strategy, Strategy::automatic);
  EXPECT_DOUBLE_EQ(c.targets.model_loads_n.uct_n, 161850);
  EXPECT_DOUBLE_EQ(c.model_specimen.thickness_m, 5.0);
  EXPECT_FALSE(c.job_template.contains("test"));
}

TEST(Campaign, BadSpecsAreRejectedNamingTheField) {
  const double nan = std::nan("");
  const std::vector<BadCase> cases = {
      {"wrong kind", {{"kind", "sweep"}}, "kind"},
      {"unknown field", {{"colour", "red"}}, "colour"},
      {"inverted bounds", {{"bounds", {{"fr0", {100, 10}}}}}, "bounds.fr0"},
      {"zero lower bound", {{"bounds", {{"fs0", {0, 10}}}}}, "bounds.fs0"},
      {"NaN bound", {{"bounds", {{"fs0", {nan, 10}}}}}, "bounds.fs0[0]"},
      {"bound not a pair", {{"bounds", {{"fr0", {1, 2, 3}}}}}, "bounds.fr0"},
      {"missing bound", {{"bounds", {{"fs0", nullptr}}}}, "bounds.fs0"},
      {"unknown bound", {{"bounds", {{"gb0", {1, 2}}}}}, "bounds.gb0"},
      {"missing targets", {{"targets", nullptr}}, "targets"},
      {"negative target", {{"targets", {{"uct", {{"peak_load", -5}}}}}}, "targets.uct.peak_load"},
      {"NaN target", {{"targets", {{"btt", {{"peak_load", nan}}}}}}, "targets.btt.peak_load"},
      {"load and strength", {{"targets", {{"btt", {{"strength", 5}}}}}}, "targets.btt.strength"},
      {"unknown target key", {{"targets", {{"btt", {{"load", 5}}}}}}, "targets.btt.load"},
      {"bad units", {{"targets", {{"units", "imperial"}}}}, "targets.units"},
      {"lab units without lab", {{"targets", {{"units", "lab"}}}}, "targets.lab"},
      {"lab block in model units", {{"targets", {{"lab", lab_targets()["lab"]}}}}, "targets.units"},
      {"missing job", {{"job", nullptr}}, "job"},
      {"job names the test", {{"job", {{"test", "uct"}}}}, "job.test"},
      {"job sets the bond", {{"job", {{"bond", {{"fr0", 1}, {"fs0", 1}}}}}}, "job.bond"},
      {"bad job field", {{"job", {{"sample", {{"diameter", -1}}}}}}, "job.sample.diameter"},
      {"unknown job key", {{"job", {{"gravity", 9.81}}}}, "job.gravity"},
      {"job nu out of range", {{"job", {{"material", {{"nu", 0.4}}}}}}, "job.material.nu"},
      {"budget too small", {{"max_evaluations", 2}}, "max_evaluations"},
      {"budget not an integer", {{"max_evaluations", 2.5}}, "max_evaluations"},
      {"zero tolerance", {{"tolerance", 0}}, "tolerance"},
      {"NaN tolerance", {{"tolerance", nan}}, "tolerance"},
      {"tolerance of 100%", {{"tolerance", 1.0}}, "tolerance"},
      {"negative weight", {{"weights", {{"uct", -1}}}}, "weights.uct"},
      {"unknown weight", {{"weights", {{"triaxial", 1}}}}, "weights.triaxial"},
      {"unknown algorithm", {{"algorithm", "lbfgs"}}, "algorithm"},
      {"unknown strategy", {{"strategy", "guess"}}, "strategy"},
      {"repeated seed", {{"seeds", {1, 2, 2}}}, "seeds[2]"},
      {"negative seed", {{"seeds", {-1}}}, "seeds[0]"},
      {"seeds not a list", {{"seeds", "1,2"}}, "seeds"},
      {"name not a string", {{"name", 5}}, "name"},
  };
  for (const BadCase& c : cases) EXPECT_EQ(field_of(c.overrides), c.field) << c.what;
}

TEST(Campaign, LabBlockErrorsNameTheirField) {
  auto with_lab = [](json lab_patch) {
    json t = lab_targets();
    t.merge_patch(lab_patch);
    return field_of({{"targets", t}});
  };
  EXPECT_EQ(with_lab({{"lab", {{"material", {{"nu", nullptr}}}}}}), "targets.lab.material.nu");
  EXPECT_EQ(with_lab({{"lab", {{"specimen", {{"diameter", 0}}}}}}),
            "targets.lab.specimen.diameter");
  EXPECT_EQ(with_lab({{"lab", {{"specimen", {{"depth", 1}}}}}}), "targets.lab.specimen.depth");
  EXPECT_EQ(with_lab({{"model_scale", {{"kr", 9000}}}}), "targets.model_scale.kr");
  EXPECT_EQ(with_lab({{"model_scale", {{"length_ratio", -3}}}}),
            "targets.model_scale.length_ratio");
  EXPECT_EQ(with_lab(json::object()), "(accepted)");
}

TEST(Campaign, RootMustBeAnObject) {
  try {
    parse_calibration_campaign(json::array());
    FAIL();
  } catch (const orch::RequestError& e) {
    EXPECT_EQ(e.field, "(root)");
  }
}

TEST(Campaign, TheMainJobRequestIsValidAndAsksForTheFourTargets) {
  std::ifstream in(ROCKCAL_SOURCE_DIR "/examples/calibrate_seed_lab.json");
  ASSERT_TRUE(in.good());
  const CalibrationCampaign c = parse_calibration_campaign(json::parse(in));
  ASSERT_TRUE(c.targets.lab.has_value());
  EXPECT_GT(c.targets.model_loads_n.uct_n, c.targets.model_loads_n.btt_n);
  // Lab UCT/BTT load ratio 311 / 51.9 = 5.99 survives the (linear) force scaling.
  EXPECT_NEAR(c.targets.model_loads_n.uct_n / c.targets.model_loads_n.btt_n, 311000.0 / 51900.0,
              1e-9);
  // The main job calibrates the field's four targets: the seed paper's E and nu (Table 1) too.
  EXPECT_EQ(c.targets.elastic.youngs_modulus_pa, 12.33e9);
  EXPECT_EQ(c.targets.elastic.poisson_ratio, 0.2);
}

// The lab load a UCT or BTT target of a benchmark request stands for: its peak load, or its
// strength on the lab specimen (UCS pi D^2 / 4, BTS pi D t / 2).
double lab_load(const json& target, const json& specimen, bool uct) {
  if (target.contains("peak_load")) return target["peak_load"].get<double>();
  const double d = specimen["diameter"].get<double>();
  const double s = target["strength"].get<double>();
  return uct ? s * std::numbers::pi * d * d / 4
             : s * std::numbers::pi * d * specimen["thickness"].get<double>() / 2;
}

// Every rock of the benchmark (a row of examples/rocks/rocks.csv) has a request the service
// accepts, and its model targets keep the rock's lab UCT/BTT load ratio: the ratio the reach of
// the specimen is judged by. Its E is a target, and its nu where the source gives one: a nu that
// stands in for a missing one sets the material, not a target the calibration must meet.
TEST(Campaign, EveryBenchmarkRockRequestIsValidKeepsItsLabRatioAndAsksForEAndTheSourcesNu) {
  std::ifstream csv(ROCKCAL_SOURCE_DIR "/examples/rocks/rocks.csv");
  ASSERT_TRUE(csv.good());
  std::string line;
  std::getline(csv, line);  // the header
  int rocks = 0;
  while (std::getline(csv, line)) {
    // The first two fields hold no comma: the rock's name and whether its source gives nu.
    const std::string rock = line.substr(0, line.find(','));
    const std::size_t from = rock.size() + 1;
    const std::string nu_from_source = line.substr(from, line.find(',', from) - from);
    ASSERT_TRUE(nu_from_source == "yes" || nu_from_source == "no") << line;
    std::ifstream in(ROCKCAL_SOURCE_DIR "/examples/rocks/" + rock + ".json");
    ASSERT_TRUE(in.good()) << rock;
    const json request = json::parse(in);
    const CalibrationCampaign c = parse_calibration_campaign(request);
    ASSERT_TRUE(c.targets.lab.has_value()) << rock;
    const json& t = request["targets"];
    const double lab_ratio = lab_load(t["uct"], t["lab"]["specimen"], true) /
                             lab_load(t["btt"], t["lab"]["specimen"], false);
    EXPECT_NEAR(c.targets.model_loads_n.uct_n / c.targets.model_loads_n.btt_n, lab_ratio,
                1e-9 * lab_ratio)
        << rock;
    // The field's four targets: E and nu as the lab's, and a further interaction range for a
    // UCS/BTS beyond touching bonds' reach.
    EXPECT_EQ(c.targets.elastic.youngs_modulus_pa,
              t["lab"]["material"]["youngs_modulus"].get<double>())
        << rock;
    if (nu_from_source == "yes") {
      EXPECT_EQ(c.targets.elastic.poisson_ratio, t["lab"]["material"]["nu"].get<double>()) << rock;
    } else {
      EXPECT_FALSE(c.targets.elastic.poisson_ratio.has_value()) << rock;
    }
    EXPECT_EQ(c.interaction_ranges, (std::vector<double>{1.0, 1.5})) << rock;
    ++rocks;
  }
  EXPECT_GE(rocks, 6) << "the benchmark's six public rocks";
}

}  // namespace
}  // namespace rockcal::calibration
