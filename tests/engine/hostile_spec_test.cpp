// Hostile job input (issue 15): JSON nested past the limit, sizes whose particle estimate
// overflows, materials that give no time step, the per-job cost limits, templates validated with
// a given bond, and packing builders asked for absurd sizes: each refused at once, with the error
// a user can act on.
#include <gtest/gtest.h>

#include <chrono>
#include <limits>

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
  json j = good();
  j["material"] = {{"density", 1e-300}, {"kr", 1e300}, {"nu", 0.2}};  // underflows to 0
  EXPECT_EQ(refusal(j),
            "material: density, stiffness and particle radius give a critical time step of 0.0 s: "
            "no usable step");
  j["material"] = {{"density", 1e300}, {"kr", 1e-300}, {"nu", 0.2}};  // overflows
  EXPECT_EQ(refusal(j).rfind("material: density, stiffness and particle radius give", 0), 0u)
      << refusal(j);
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
