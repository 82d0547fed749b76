// Bad job specs are refused with an error that names the field.
#include <gtest/gtest.h>

#include <limits>

#include "engine/spec.hpp"

using namespace rockcal;
using nlohmann::json;

namespace {

json good() {
  return json::parse(R"({"test": "uct",
    "sample": {"diameter": 10, "height": 28, "packing": "fcc", "radius": 1.0, "seed": 1},
    "material": {"density": 1.0, "kr": 8000, "nu": 0.2},
    "bond": {"fr0": 64, "fs0": 64}, "contact": {"friction": 0.6},
    "loading": {"platen_velocity": 0.05, "dt": "auto", "stop_load_fraction": 0.7, "max_strain": 0.05},
    "damping": {"local": 0.7}})");
}

std::string field_of(const json& j) {
  try {
    parse_job(j);
  } catch (const SpecError& e) {
    return e.field;
  }
  return "(accepted)";
}

}  // namespace

TEST(Spec, AcceptsTheDocumentedExampleAndFillsDefaults) {
  const JobSpec s = parse_job(good());
  EXPECT_EQ(s.test, TestKind::uct);
  EXPECT_DOUBLE_EQ(s.sample.btt_thickness(), 5.0);  // D / 2 by default
  const json c = to_json(s);
  EXPECT_EQ(c["loading"]["dt"], "auto");
  EXPECT_EQ(to_json(parse_job(c)), c);  // canonical form is a fixed point
}

TEST(Spec, NamesTheOffendingField) {
  auto with = [](const std::string& ptr, json v) {
    json j = good();
    j[json::json_pointer(ptr)] = std::move(v);
    return j;
  };
  EXPECT_EQ(field_of(with("/sample/colour", "red")), "sample.colour");
  EXPECT_EQ(field_of(with("/extra", 1)), "extra");
  EXPECT_EQ(field_of(with("/material/kr", -5)), "material.kr");
  EXPECT_EQ(field_of(with("/material/kr", "8000")), "material.kr");
  EXPECT_EQ(field_of(with("/material/kr", std::numeric_limits<double>::quiet_NaN())),
            "material.kr");
  EXPECT_EQ(field_of(with("/material/nu", 0.4)), "material.nu");
  EXPECT_EQ(field_of(with("/material/youngs_modulus", 1e9)),
            "material.youngs_modulus");  // both given
  EXPECT_EQ(field_of(with("/bond/fr0", 0)), "bond.fr0");
  EXPECT_EQ(field_of(with("/sample/diameter", 1e6)), "sample.diameter");  // absurd size
  EXPECT_EQ(field_of(with("/sample/radius", std::numeric_limits<double>::infinity())),
            "sample.radius");
  EXPECT_EQ(field_of(with("/loading/dt", "fast")), "loading.dt");
  EXPECT_EQ(field_of(with("/loading/dt", 10.0)), "loading.dt");  // above the stability limit
  EXPECT_EQ(field_of(with("/loading/max_steps", 1.5)), "loading.max_steps");
  EXPECT_EQ(field_of(with("/damping/local", 1.0)), "damping.local");
  EXPECT_EQ(field_of(with("/test", "triaxial")), "test");
  EXPECT_EQ(field_of(with("/sample/packing", "hcp")), "sample.packing");
  EXPECT_EQ(field_of(json::array()), "(root)");
  json no_bond = good();
  no_bond.erase("bond");
  EXPECT_EQ(field_of(no_bond), "bond");
}

TEST(Spec, TemplatesMustNotNameTheTest) {
  json t = good();
  EXPECT_THROW(parse_job_template(t, TestKind::btt), SpecError);
  t.erase("test");
  EXPECT_EQ(parse_job_template(t, TestKind::btt).test, TestKind::btt);
}
