// Hostile job input: JSON nested past the limit, sizes whose particle estimate overflows,
// materials that give no time step, absurd physical values, the per-job cost limits (particles
// and time steps), templates validated with a given bond, and packing builders asked for absurd
// sizes: each refused at once, with the error a user can act on.
#include <gtest/gtest.h>

#include <chrono>
#include <limits>
#include <vector>

#include "engine/json_input.hpp"
#include "engine/packing/fcc.hpp"
#include "engine/packing/random_dense.hpp"
#include "engine/spec.hpp"

using namespace rockcal;
using nlohmann::json;

namespace {

// The small UCT of examples/uct_small.json, reduced to what the tests below vary.
json good() {
  return {{"test", "uct"},
          {"sample", {{"diameter", 10}, {"height", 28}, {"radius", 1.0}}},
          {"material", {{"kr", 8000}}},
          {"bond", {{"fr0", 64}, {"fs0", 64}}}};
}

json with(const std::string& pointer, json value) {
  json j = good();
  j[json::json_pointer(pointer)] = std::move(value);
  return j;
}

// "field: message" of the refusal, or "(accepted)".
std::string refusal(const json& j) {
  try {
    parse_job(j);
  } catch (const SpecError& e) {
    return e.what();
  }
  return "(accepted)";
}

std::string input_error(const std::string& text) {
  try {
    parse_json_input(text);
  } catch (const JsonInputError& e) {
    return e.what();
  }
  return "(parsed)";
}

std::string nested(int levels, const char* open, const char* close) {
  std::string s;
  for (int i = 0; i < levels; ++i) s += open;
  s += "1";
  for (int i = 0; i < levels; ++i) s += close;
  return s;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

TEST(HostileSpec, JsonNestedPastTheLimitIsRefusedWhileParsing) {
  const std::string too_deep = "JSON nested deeper than 64 levels (the limit)";
  EXPECT_EQ(input_error(nested(64, "[", "]")), "(parsed)");
  EXPECT_EQ(input_error(nested(63, "{\"a\":", "}")), "(parsed)");
  EXPECT_EQ(input_error(nested(65, "[", "]")), too_deep);
  EXPECT_EQ(input_error(nested(65, "{\"a\":", "}")), too_deep);
  // Refused at level 65, whatever follows: parsing stops there.
  const std::string objects = nested(1000000, "{\"a\":", "}"), arrays(10000000, '[');
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(input_error(objects), too_deep);
  EXPECT_EQ(input_error(arrays), too_deep);
  EXPECT_LT(seconds_since(t0), 0.1);
  EXPECT_EQ(
      input_error("{\"a\": 1e999}").rfind("malformed JSON: [json.exception.out_of_range.406]", 0),
      0u);
  EXPECT_EQ(input_error("{\"packing\": \"fc\xff\"}")
                .rfind("malformed JSON: [json.exception.parse_error.101]", 0),
            0u);
}

TEST(HostileSpec, AKeyGivenTwiceInOneObjectIsRefusedNamingIt) {
  EXPECT_EQ(input_error(R"({"test": "uct", "test": "btt"})"), "test: given more than once");
  EXPECT_EQ(input_error(R"({"bond": {"fr0": 1, "fs0": 2, "fr0": 3}})"),
            "bond.fr0: given more than once");
  EXPECT_EQ(input_error(R"({"points": [{"fr0": 1}, {"fs0": 1, "fs0": 2}]})"),
            "points.fs0: given more than once");
  try {
    parse_json_input(R"({"job": {"loading": {"dt": 1, "dt": "auto"}}})");
    ADD_FAILURE() << "accepted a duplicate key";
  } catch (const JsonInputError& e) {
    EXPECT_EQ(e.field, "job.loading.dt");
  }
  // The same key in different objects, and in objects of one array, is no duplicate.
  EXPECT_EQ(input_error(R"({"a": {"k": 1}, "b": {"k": 2}, "c": [{"k": 1}, {"k": 1}]})"),
            "(parsed)");
}

TEST(HostileSpec, AParticleEstimateThatOverflowsIsRefused) {
  // inf / inf was NaN at 64e168e, and NaN > cap is false: the spec passed, the run never ended.
  json huge = good();
  huge["sample"] = {{"diameter", 1e308}, {"height", 1e308}, {"radius", 1e300}};
  EXPECT_EQ(refusal(huge),
            "sample.diameter: specimen would hold about 1.39e+23 particles (limit 2000000)");
  huge["sample"] = {{"diameter", 1e200}, {"height", 1e200}, {"radius", 1e-200}};
  EXPECT_EQ(
      refusal(huge),
      "sample.diameter: specimen would hold an unbounded number of particles (limit 2000000)");
  huge["sample"] = {{"diameter", 200}, {"height", 400}, {"radius", 1}};
  EXPECT_EQ(refusal(huge),
            "sample.diameter: specimen would hold about 2221441 particles (limit 2000000)");
  huge["sample"] = {{"diameter", 180}, {"height", 400}, {"radius", 1}};
  EXPECT_EQ(refusal(huge), "(accepted)");
}

TEST(HostileSpec, MaterialsThatGiveNoUsableTimeStepAreRefused) {
  // Each value within its bounds, the three together give no step: a grain of 1e-200 m weighs 0.
  json j = good();
  j["sample"] = {{"diameter", 1e-199}, {"height", 3e-199}, {"radius", 1e-200}};
  EXPECT_EQ(refusal(j),
            "material: density, stiffness and particle radius give a critical time step of 0 s: "
            "no usable step");
  j["sample"] = {{"diameter", 1e201}, {"height", 3e201}, {"radius", 1e200}};  // overflows
  EXPECT_EQ(refusal(j),
            "material: density, stiffness and particle radius give a critical time step of inf s: "
            "no usable step");
}

TEST(HostileSpec, AbsurdPhysicalValuesAreRefusedNamingTheField) {
  struct Case {
    std::string pointer;
    double value;
    std::string refusal;
  };
  for (const auto& k : std::vector<Case>{
           {"/material/kr", 1e20,
            "material.kr: must be in [1e-06, 1e+13] N/m; 1e+20 is absurd in SI and in model units"},
           {"/material/youngs_modulus", 1e-300,
            "material.youngs_modulus: must be in [1e-06, 1e+13] Pa; 1e-300 is absurd in SI and in "
            "model units"},
           {"/material/density", 1e-300,
            "material.density: must be in [1e-06, 1e+06] kg/m^3; 1e-300 is absurd in SI and in "
            "model units"},
           {"/material/density", 1e300,
            "material.density: must be in [1e-06, 1e+06] kg/m^3; 1e+300 is absurd in SI and in "
            "model units"},
           {"/loading/platen_velocity", 1e-300,
            "loading.platen_velocity: must be in [1e-09, 1e+03] m/s; 1e-300 is absurd in SI and in "
            "model units"},
           {"/loading/platen_velocity", 1e300,
            "loading.platen_velocity: must be in [1e-09, 1e+03] m/s; 1e+300 is absurd in SI and in "
            "model units"},
           {"/loading/dt", 1e-300,
            "loading.dt: must be in [1e-15, 1e+03] s; 1e-300 is absurd in SI and in model units"},
       }) {
    json j = good();
    if (k.pointer == "/material/youngs_modulus") j["material"].erase("kr");
    j[json::json_pointer(k.pointer)] = k.value;
    EXPECT_EQ(refusal(j), k.refusal) << k.pointer;
  }
  // In bounds, yet faster than a tenth of the wave speed (95.7 m/s for this material): an impact.
  EXPECT_EQ(refusal(with("/loading/platen_velocity", 20.0)),
            "loading.platen_velocity: 20.0 m/s is over 0.1 of the specimen's wave speed (95.7 m/s "
            "from material and sample): an impact, not a quasi-static test");
  EXPECT_EQ(refusal(with("/loading/platen_velocity", 9.0)), "(accepted)");
}

TEST(HostileSpec, EveryJobHasABoundedStepCount) {
  // The small UCT's step count grows as 1 / platen speed.
  EXPECT_EQ(refusal(with("/loading/platen_velocity", 1e-6)),
            "loading.platen_velocity: 1e-06 m/s against a wave speed of 95.7 m/s gives the job "
            "about 183728400 time steps (limit 100000000)");
  EXPECT_EQ(refusal(with("/loading/platen_velocity", 2e-6)), "(accepted)");
  // A given step far below the automatic one is what makes the run long: it is named.
  EXPECT_EQ(refusal(with("/loading/dt", 1e-9)),
            "loading.dt: of 1e-09 s gives the job about 1.72e+10 time steps (limit 100000000)");
  // A stiffer material at the same speed: the wave speed, and the steps, grow with sqrt(kr).
  EXPECT_EQ(refusal(with("/material/kr", 1e13)),
            "loading.platen_velocity: 0.05 m/s against a wave speed of 3.39e+06 m/s gives the job "
            "about 129915707 time steps (limit 100000000)");
  // Two-rate loading and a rate study multiply the runs' length: the field that did is named.
  json slow = with("/loading/platen_velocity", 5e-5);
  EXPECT_EQ(refusal(slow), "(accepted)");
  slow["loading"]["slow_factor"] = 0.01;
  EXPECT_EQ(refusal(slow),
            "loading.slow_factor: gives the job about 356860850 time steps (limit 100000000)");
  json study = with("/loading/platen_velocity", 2e-4);
  study["loading"]["rate_study"] = true;
  study["loading"]["rate_study_runs"] = 6;
  EXPECT_EQ(refusal(study),
            "loading.rate_study_runs: gives the job about 116669906 time steps in all its runs "
            "(limit 100000000)");
  study["loading"]["rate_study"] = false;
  EXPECT_EQ(refusal(study), "(accepted)");
  // A step limit bounds each run whatever the speed.
  json capped = with("/loading/platen_velocity", 1e-6);
  capped["loading"]["max_steps"] = 1000000;
  EXPECT_EQ(refusal(capped), "(accepted)");
}

TEST(HostileSpec, PerJobCostLimits) {
  EXPECT_EQ(refusal(with("/loading/max_steps", 100000001)),
            "loading.max_steps: must be in [1, 100000000]");
  EXPECT_EQ(refusal(with("/loading/max_steps", 10000000000LL)),
            "loading.max_steps: must be in [1, 100000000]");
  EXPECT_EQ(refusal(with("/loading/max_steps", 100000000)), "(accepted)");
  EXPECT_EQ(refusal(with("/output/curve_points", 100001)),
            "output.curve_points: must be in [10, 100000]");
  EXPECT_EQ(refusal(with("/output/curve_points", 100000)), "(accepted)");
  EXPECT_EQ(refusal(with("/output/vtk_frames", 1001)), "output.vtk_frames: must be in [1, 1000]");
  // VTK frames x particles: 1000 frames of the D = 10 R sample pass, of a 278k-particle one not.
  json vtk = with("/output", {{"vtk", true}, {"vtk_frames", 1000}});
  EXPECT_EQ(refusal(vtk), "(accepted)");
  vtk["sample"] = {{"diameter", 100}, {"height", 200}, {"radius", 1}};
  EXPECT_EQ(refusal(vtk).rfind("output.vtk_frames: frames x particles is about 277680", 0), 0u)
      << refusal(vtk);
  vtk["output"]["vtk"] = false;  // no VTK written: the frame count costs nothing
  EXPECT_EQ(refusal(vtk), "(accepted)");
}

TEST(HostileSpec, ATemplateWithAGivenBondIsValidatedAsItStands) {
  json tmpl = good();
  tmpl.erase("test");
  tmpl.erase("bond");
  json full = good();
  full["bond"] = {{"fr0", 12.5}, {"fs0", 40}};
  EXPECT_EQ(parse_job_template(tmpl, TestKind::uct, BondSpec{12.5, 40}), parse_job(full));
  tmpl["bond"] = {{"fr0", "overwritten"}};  // a sweep's template may name the strengths it sets
  EXPECT_EQ(parse_job_template(tmpl, TestKind::uct, BondSpec{12.5, 40}), parse_job(full));
  tmpl["bond"] = {{"fr0", 1}, {"colour", "red"}};
  try {
    parse_job_template(tmpl, TestKind::uct, BondSpec{12.5, 40});
    ADD_FAILURE() << "accepted an unknown bond field";
  } catch (const SpecError& e) {
    EXPECT_EQ(std::string(e.what()), "bond.colour: unknown field");
  }
  tmpl["bond"] = 5;
  try {
    parse_job_template(tmpl, TestKind::uct, BondSpec{12.5, 40});
    ADD_FAILURE() << "accepted a bond that is not an object";
  } catch (const SpecError& e) {
    EXPECT_EQ(std::string(e.what()), "bond: must be a JSON object");
  }
}

TEST(HostileSpec, PackingBuildersRefuseAbsurdSizesAtOnce) {
  // At 64e168e the FCC walk looped over ~1e23 lattice sites for these.
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_THROW(fcc_centres(Cylinder{1e308, 1e308}, 1e300), std::length_error);
  EXPECT_THROW(fcc_centres(Disc{1e308, 1e308}, 1e300), std::length_error);
  EXPECT_THROW(fcc_centres(Cylinder{1e6, 1e6}, 1.0), std::length_error);
  EXPECT_THROW(fcc_centres(Cylinder{10, 10}, std::numeric_limits<double>::quiet_NaN()),
               std::length_error);
  EXPECT_THROW(random_dense_spheres(Cylinder{1e4, 1e4}, {1.0, 1.5, 1}), std::length_error);
  EXPECT_THROW(random_dense_spheres(Disc{1e308, 1e308}, {1e300, 1.5, 1}), std::length_error);
  EXPECT_LT(seconds_since(t0), 1.0);
  EXPECT_FALSE(fcc_centres(Cylinder{10, 28}, 1.0).empty());  // a real specimen still builds
}
