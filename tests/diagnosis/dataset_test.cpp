// The lab dataset format: strict parsing that names the field, JSON <-> CSV equivalence, and the
// lab -> model mapping (eq. 4) agreeing with the calibration campaign's.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>

#include "orchestrator/calibration/campaign.hpp"
#include "orchestrator/diagnosis/dataset/dataset.hpp"

namespace rockcal::diagnosis {
namespace {

using nlohmann::json;

std::string example(const std::string& name) {
  return std::string(ROCKCAL_SOURCE_DIR) + "/examples/" + name;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

json read_json(const std::string& path) {
  return json::parse(read_text(path));
}

json model_dataset() {
  return {{"name", "small"},
          {"units", "model"},
          {"observations",
           {{{"id", "uct-1"},
             {"test", "uct"},
             {"conditions", {{"diameter", 8}, {"height", 16}}},
             {"observable", "peak_load"},
             {"value", 1000.0},
             {"uncertainty", 20.0},
             {"role", "calibration"}},
            {{"id", "btt-1"},
             {"test", "btt"},
             {"observable", "peak_load"},
             {"value", 150.0},
             {"uncertainty", 3.0},
             {"role", "held_out"}}}}};
}

// The field an invalid dataset is refused for ("" when it parses).
std::string refused_field(const json& j) {
  try {
    parse_dataset_json(j);
  } catch (const orch::RequestError& e) {
    return e.field;
  }
  return "";
}

std::string refused_csv_field(const std::string& text, std::string* message = nullptr) {
  try {
    parse_dataset_csv(text);
  } catch (const orch::RequestError& e) {
    if (message) *message = e.what();
    return e.field;
  }
  return "";
}

TEST(DiagnosisDataset, ErrorsNameTheField) {
  ASSERT_EQ(refused_field(model_dataset()), "");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<std::function<void(json&)>, std::string>> cases = {
      {[](json& j) { j["colour"] = "red"; }, "colour"},
      {[](json& j) { j["observations"][1]["weight"] = 2; }, "observations[1].weight"},
      {[](json& j) { j["observations"][0]["conditions"]["radius"] = 1; },
       "observations[0].conditions.radius"},
      {[&](json& j) { j["observations"][1]["value"] = nan; }, "observations[1].value"},
      {[](json& j) { j["observations"][1]["value"] = 0; }, "observations[1].value"},
      {[](json& j) { j["observations"][1]["value"] = "150"; }, "observations[1].value"},
      {[](json& j) { j["observations"][1]["uncertainty"] = -3; }, "observations[1].uncertainty"},
      {[](json& j) { j["observations"][1].erase("uncertainty"); }, "observations[1].uncertainty"},
      {[](json& j) { j["observations"][1]["test"] = "elastic"; }, "observations[1].test"},
      {[](json& j) { j["observations"][1]["test"] = "shear"; }, "observations[1].test"},
      {[](json& j) { j["observations"][1]["observable"] = "bts"; }, "observations[1].observable"},
      {[](json& j) { j["observations"][1]["observable"] = "youngs_modulus"; },
       "observations[1].observable"},
      {[](json& j) { j["observations"][1]["observable"] = "peak_strain"; },
       "observations[1].observable"},
      {[](json& j) { j["observations"][1]["role"] = "validation"; }, "observations[1].role"},
      {[](json& j) { j["observations"][1]["id"] = "uct-1"; }, "observations[1].id"},
      {[](json& j) { j["observations"][1]["id"] = ""; }, "observations[1].id"},
      {[](json& j) { j["observations"][0]["role"] = "held_out"; }, "observations"},
      {[](json& j) { j["observations"] = json::array(); }, "observations"},
      {[](json& j) { j["observations"][0]["conditions"]["confining_pressure"] = 1e3; },
       "observations[0].conditions.confining_pressure"},
      {[](json& j) { j["observations"][0]["conditions"]["thickness"] = 4; },
       "observations[0].conditions.thickness"},
      {[](json& j) {
         j["observations"][1]["conditions"] = {{"height", 4}};
       },
       "observations[1].conditions.height"},
      {[](json& j) { j["observations"][0]["conditions"]["diameter"] = -8; },
       "observations[0].conditions.diameter"},
      {[](json& j) { j["units"] = "lab"; }, "lab"},
      {[](json& j) { j["units"] = "si"; }, "units"},
      {[](json& j) { j["origin"] = "twin"; }, "origin"},
      {[](json& j) {
         j["model_scale"] = {{"kr", 8000}};
       },
       "units"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    json j = model_dataset();
    cases[i].first(j);
    EXPECT_EQ(refused_field(j), cases[i].second) << "case " << i << ": " << j.dump();
  }
}

// Who made the numbers travels with them (the budget charges each origin its own errors), in both
// forms; a dataset that does not say is lab data, so it is charged every error.
TEST(DiagnosisDataset, OriginIsKeptAndDefaultsToLab) {
  EXPECT_EQ(parse_dataset_json(model_dataset()).origin, Origin::lab);
  for (const Origin o : {Origin::lab, Origin::same_resolution_model, Origin::finer_model}) {
    json j = model_dataset();
    j["origin"] = to_string(o);
    const Dataset d = parse_dataset_json(j);
    EXPECT_EQ(d.origin, o);
    EXPECT_EQ(parse_dataset_json(to_json(d)).origin, o);
    EXPECT_EQ(parse_dataset_csv(to_csv(d)).origin, o);
  }
  json j = model_dataset();
  j["origin"] = "twin";
  try {
    parse_dataset_json(j);
    ADD_FAILURE() << "accepted origin \"twin\"";
  } catch (const orch::RequestError& e) {
    EXPECT_STREQ(e.what(), "origin: must be \"lab\", \"same_resolution_model\" or \"finer_model\"");
  }
}

TEST(DiagnosisDataset, TriaxialNeedsItsConfiningPressure) {
  json j = model_dataset();
  j["observations"][1] = {{"id", "tri-1"}, {"test", "triaxial"}, {"observable", "strength"},
                          {"value", 3.0},  {"uncertainty", 0.1}, {"role", "held_out"}};
  EXPECT_EQ(refused_field(j), "observations[1].conditions.confining_pressure");
  j["observations"][1]["conditions"] = {{"diameter", 8}};
  EXPECT_EQ(refused_field(j), "observations[1].conditions.confining_pressure");
  j["observations"][1]["conditions"]["confining_pressure"] = 0;
  EXPECT_EQ(refused_field(j), "observations[1].conditions.confining_pressure");
  j["observations"][1]["conditions"]["confining_pressure"] = 0.5;
  EXPECT_EQ(refused_field(j), "");
}

TEST(DiagnosisDataset, LabUnitsNeedTheLabBlockAndTheModelScale) {
  json j = read_json(example("datasets/seed_lab.json"));
  ASSERT_EQ(refused_field(j), "");
  json no_scale = j;
  no_scale.erase("model_scale");
  EXPECT_EQ(refused_field(no_scale), "model_scale");
  json partial_scale = j;
  partial_scale["model_scale"].erase("kr");
  EXPECT_EQ(refused_field(partial_scale), "model_scale.kr");
  json bad_material = j;
  bad_material["lab"]["material"]["nu"] = 0.6;
  EXPECT_EQ(refused_field(bad_material), "lab.material.nu");
  json no_lab = j;
  no_lab.erase("lab");
  EXPECT_EQ(refused_field(no_lab), "lab");
}

TEST(DiagnosisDataset, CsvErrorsNameTheFieldAndTheLine) {
  const std::string header =
      "id,test,diameter,height,thickness,confining_pressure,loading_rate,observable,value,"
      "uncertainty,role\n";
  const std::string good = "uct-1,uct,8,16,,,,peak_load,1000,20,calibration\n";
  std::string message;
  EXPECT_EQ(refused_csv_field("# units: model\n" + header + good), "");
  EXPECT_EQ(
      refused_csv_field(header + good + "btt-1,btt,8,,4,,,peak_load,150,abc,held_out\n", &message),
      "observations[1].uncertainty");
  EXPECT_NE(message.find("'abc' is not a number"), std::string::npos) << message;
  EXPECT_EQ(refused_csv_field(header + good + "btt-1,btt,8,,4,,,peak_load,nan,3,held_out\n"),
            "observations[1].value");
  EXPECT_EQ(refused_csv_field(header + "\n" + good + "btt-1,btt,8,,4,,,peak_load,150,0,held_out\n",
                              &message),
            "observations[1].uncertainty");
  EXPECT_NE(message.find("(line 4)"), std::string::npos) << message;
  EXPECT_EQ(refused_csv_field(header + good + "btt-1,btt,8,,4,,,peak_load,150,3\n"),
            "observations[1]");
  EXPECT_EQ(refused_csv_field("id,test,value\n" + good), "(header)");
  EXPECT_EQ(refused_csv_field("# unit: lab\n" + header + good), "unit");
  EXPECT_EQ(refused_csv_field(header + "# units: lab\n" + good), "units");
  EXPECT_EQ(refused_csv_field("# units: lab\n# lab: {oops\n" + header + good), "lab");
  EXPECT_EQ(refused_csv_field("# units: lab\n" + header + good), "lab");
  // A free comment (not "# word:") is just a comment.
  EXPECT_EQ(refused_csv_field("# Table 1, as printed\n" + header + good), "");
}

TEST(DiagnosisDataset, ExamplesParseInBothForms) {
  for (const std::string name : {"seed_lab", "zigong_triaxial"}) {
    const Dataset from_json = read_dataset_file(example("datasets/" + name + ".json"));
    const Dataset from_csv = read_dataset_file(example("datasets/" + name + ".csv"));
    EXPECT_EQ(to_json(from_json), to_json(from_csv)) << name;
    EXPECT_TRUE(from_json.lab.has_value()) << name;
    EXPECT_FALSE(from_json.note.empty()) << name;
    // Round trips: JSON -> struct -> JSON and struct -> CSV -> struct.
    EXPECT_EQ(to_json(parse_dataset_json(to_json(from_json))), to_json(from_json)) << name;
    EXPECT_EQ(to_json(parse_dataset_csv(to_csv(from_json))), to_json(from_json)) << name;
  }
  const Dataset seed = read_dataset_file(example("datasets/seed_lab.json"));
  ASSERT_EQ(seed.observations.size(), 2u);
  EXPECT_EQ(seed.observations[0].value, 311000);
  EXPECT_EQ(seed.observations[1].value, 51900);
  {
    const Dataset zigong = read_dataset_file(example("datasets/zigong_triaxial.json"));
    int calibration = 0, held_out = 0;
    for (const Observation& o : zigong.observations) {
      (o.role == Role::calibration ? calibration : held_out)++;
      // Calibrated on the UCS and one triaxial point (20 MPa); the rest of the curve is held out.
      const bool at_20_mpa = o.conditions.confining_pressure_pa == 20e6;
      EXPECT_EQ(o.role == Role::calibration, o.test == TestKind::uct || at_20_mpa) << o.id;
      EXPECT_EQ(o.observable, Observable::strength) << o.id;
    }
    EXPECT_EQ(calibration, 7);
    EXPECT_EQ(held_out, 14);
  }
}

TEST(DiagnosisDataset, ModelUnitsRoundTripThroughCsv) {
  const Dataset d = parse_dataset_json(model_dataset());
  EXPECT_EQ(to_json(parse_dataset_csv(to_csv(d))), to_json(d));
  EXPECT_EQ(to_json(in_model_units(d)), to_json(d));  // nothing to map
}

// The seed dataset and examples/calibrate_seed_lab.json describe the same lab case with the same
// model scale, so they must ask the model for the same loads.
TEST(DiagnosisDataset, SeedLabMapsToTheCalibrationExamplesTargets) {
  const Dataset seed = read_dataset_file(example("datasets/seed_lab.json"));
  const auto campaign =
      calibration::parse_calibration_campaign(read_json(example("calibrate_seed_lab.json")));
  const Observation uct = to_model_units(seed.observations[0], seed);
  const Observation btt = to_model_units(seed.observations[1], seed);
  EXPECT_NEAR(uct.value / campaign.targets.model_loads_n.uct_n, 1.0, 1e-12);
  EXPECT_NEAR(btt.value / campaign.targets.model_loads_n.btt_n, 1.0, 1e-12);
  EXPECT_NEAR(uct.uncertainty / uct.value, 0.05, 1e-12);
  // The lab specimen maps to the demo sample's height (x2/x1 = 28 / 0.14705).
  EXPECT_NEAR(*uct.conditions.height_m, 28.0, 1e-3);
  EXPECT_NEAR(*btt.conditions.thickness_m, 0.5 * *btt.conditions.diameter_m, 1e-9);

  // At the paper's own scale (x2/x1 = H2/H1 = 139 / 0.14705) the UCT maps to 161,850 N.
  json paper = to_json(seed);
  paper["model_scale"]["length_ratio"] = 139 / 0.14705;
  const Dataset at_paper_scale = parse_dataset_json(paper);
  EXPECT_NEAR(to_model_units(at_paper_scale.observations[0], at_paper_scale).value / 161850, 1.0,
              5e-4);
  EXPECT_NEAR(at_paper_scale.scaling->kr_lab_n_m, 1.453e7, 0.001e7);
}

TEST(DiagnosisDataset, LabConditionsMapByTheirOwnScale) {
  const Dataset seed = read_dataset_file(example("datasets/seed_lab.json"));
  const Scaling& s = *seed.scaling;
  json j = to_json(seed);
  j["observations"][0]["observable"] = "strength";
  j["observations"][0]["value"] = 133.5e6;
  j["observations"][0]["conditions"] = {{"loading_rate", 4.2167e-6}};  // dimensions: the lab's
  j["observations"][1]["observable"] = "peak_load";
  {
    j["observations"].push_back({{"id", "tri-1"},
                                 {"test", "triaxial"},
                                 {"conditions", {{"confining_pressure", 20e6}}},
                                 {"observable", "youngs_modulus"},
                                 {"value", 12e9},
                                 {"uncertainty", 1e9},
                                 {"role", "held_out"}});
    j["observations"].push_back({{"id", "uct-strain"},
                                 {"test", "uct"},
                                 {"observable", "peak_strain"},
                                 {"value", 0.004},
                                 {"uncertainty", 0.0004},
                                 {"role", "held_out"}});
  }
  const Dataset d = parse_dataset_json(j);
  {
    // A strain has no unit: the lab's 0.4% is the model's.
    const Observation strain = to_model_units(d.observations[3], d);
    EXPECT_EQ(strain.observable, Observable::peak_strain);
    EXPECT_DOUBLE_EQ(strain.value, 0.004);
    EXPECT_DOUBLE_EQ(strain.uncertainty, 0.0004);
  }
  const Observation ucs = to_model_units(d.observations[0], d);
  EXPECT_DOUBLE_EQ(ucs.value, 133.5e6 * s.stress);
  EXPECT_DOUBLE_EQ(*ucs.conditions.diameter_m, 0.05446 * s.length);
  EXPECT_DOUBLE_EQ(*ucs.conditions.height_m, 0.14705 * s.length);
  EXPECT_FALSE(ucs.conditions.thickness_m.has_value());
  EXPECT_DOUBLE_EQ(*ucs.conditions.loading_rate_m_s, 4.2167e-6 * s.velocity);
  EXPECT_NEAR(s.stress, s.force / (s.length * s.length), 1e-12 * s.stress);
  {
    const Observation tri = to_model_units(d.observations[2], d);
    EXPECT_DOUBLE_EQ(tri.conditions.confining_pressure_pa, 20e6 * s.stress);
    EXPECT_DOUBLE_EQ(tri.value, 12e9 * s.stress);
    EXPECT_DOUBLE_EQ(tri.uncertainty, 1e9 * s.stress);
  }
  const Dataset m = in_model_units(d);
  EXPECT_FALSE(m.lab.has_value());
  EXPECT_EQ(to_json(m)["units"], "model");
  EXPECT_EQ(refused_field(to_json(m)), "");
}

TEST(DiagnosisDataset, ModelScaleMustBeTheTemplates) {
  const Dataset seed = read_dataset_file(example("datasets/seed_lab.json"));
  json job = {{"test", "uct"},
              {"sample", {{"diameter", 10}, {"height", 28}, {"radius", 1}}},
              {"material", {{"kr", 8000}, {"nu", 0.2}, {"density", 1}}},
              {"bond", {{"fr0", 64}, {"fs0", 64}}}};
  EXPECT_NO_THROW(check_model_scale(seed, parse_job(job)));
  job["material"]["kr"] = 9000;
  try {
    check_model_scale(seed, parse_job(job));
    ADD_FAILURE() << "a different K_r was accepted";
  } catch (const orch::RequestError& e) {
    EXPECT_EQ(e.field, "model_scale.kr");
  }
}

}  // namespace
}  // namespace rockcal::diagnosis
