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
  EXPECT_EQ(field_of(with("/test", "hydrostatic")), "test");
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

TEST(Spec, EffectsAreCheckedNamingTheField) {
  auto with_effects = [](json effects) {
    json j = good();
    j["effects"] = std::move(effects);
    return j;
  };
  EXPECT_EQ(field_of(with_effects({{"gravity", json::object()}})), "effects.gravity");
  try {
    parse_job(with_effects({{"gravity", json::object()}}));
  } catch (const SpecError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown effect (known: heterogeneity, packing"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(field_of(with_effects({{"rate", {{"speed", 2}}}})), "effects.rate.speed");
  try {
    parse_job(with_effects({{"rate", {{"speed", 2}}}}));
  } catch (const SpecError& e) {
    EXPECT_EQ(std::string(e.what()), "effects.rate.speed: unknown field");
  }
  EXPECT_EQ(field_of(with_effects({{"heterogeneity", {{"weibull_m", 1.0}}}})),
            "effects.heterogeneity.weibull_m");
  EXPECT_EQ(field_of(with_effects({{"flaws", {{"crack_radius", 21}}}})),
            "effects.flaws.crack_radius");
  EXPECT_EQ(field_of(with_effects({{"rate", {{"speed_factor", "fast"}}}})),
            "effects.rate.speed_factor");
  EXPECT_EQ(field_of(with_effects(
                {{"rate", {{"speed_factor", std::numeric_limits<double>::quiet_NaN()}}}})),
            "effects.rate.speed_factor");
  EXPECT_EQ(field_of(with_effects({{"rate", 4}})), "effects.rate");
  EXPECT_EQ(field_of(with_effects(json::array())), "effects");
  EXPECT_EQ(field_of(with_effects(json::object())), "(accepted)");
}

TEST(Spec, EffectsStayInTheCanonicalFormAsWritten) {
  json j = good();
  j["effects"] = {{"rate", json::object()}, {"flaws", {{"fraction", 0.1}}}};
  const JobSpec s = parse_job(j);
  ASSERT_EQ(s.effects.size(), 2u);
  EXPECT_EQ(s.effects.at("rate").at("speed_factor"), 4.0);  // default filled in
  EXPECT_EQ(s.effects.at("flaws").at("crack_radius"), 0.0);
  EXPECT_DOUBLE_EQ(*s.loading.platen_velocity_m_s, 0.05);                 // the job as written ...
  EXPECT_DOUBLE_EQ(*effective_spec(s).loading.platen_velocity_m_s, 0.2);  // ... and as run
  const json c = to_json(s);
  EXPECT_EQ(c["effects"]["rate"]["speed_factor"], 4.0);
  EXPECT_EQ(c["loading"]["platen_velocity"], 0.05);
  // Idempotent: parsing the canonical form gives the same job, not a compounded speed.
  EXPECT_EQ(parse_job(c), s);
  EXPECT_EQ(to_json(parse_job(c)), c);
  EXPECT_DOUBLE_EQ(*effective_spec(parse_job(c)).loading.platen_velocity_m_s, 0.2);
  // A job without effects keeps the canonical form (and identity) it had before effects existed.
  EXPECT_FALSE(to_json(parse_job(good())).contains("effects"));
  // A spec-changing effect's values are validated as the run will see them.
  j["effects"] = {{"packing", {{"radius_ratio", 2}}}};
  EXPECT_EQ(effective_spec(parse_job(j)).sample.packing, "random");
  EXPECT_EQ(parse_job(to_json(parse_job(j))), parse_job(j));
}

TEST(Spec, TriaxialTakesAConfiningPressure) {
  json j = good();
  j["test"] = "triaxial";
  EXPECT_EQ(parse_job(j).loading.confining_pressure_pa, 0.0);
  j["loading"]["confining_pressure"] = 25.0;
  const JobSpec s = parse_job(j);
  EXPECT_EQ(s.test, TestKind::triaxial);
  EXPECT_EQ(s.loading.confining_pressure_pa, 25.0);
  EXPECT_EQ(to_json(s)["test"], "triaxial");
  EXPECT_EQ(to_json(s)["loading"]["confining_pressure"], 25.0);
  EXPECT_EQ(parse_job(to_json(s)), s);
  j["loading"]["confining_pressure"] = -1.0;
  EXPECT_EQ(field_of(j), "loading.confining_pressure");
  j["loading"]["confining_pressure"] = "high";
  EXPECT_EQ(field_of(j), "loading.confining_pressure");
  j["test"] = "uct";
  j["loading"]["confining_pressure"] = 25.0;
  EXPECT_EQ(field_of(j), "loading.confining_pressure");  // only the triaxial test is confined
  EXPECT_FALSE(to_json(parse_job(good()))["loading"].contains("confining_pressure"));
}
