// Focus: one twin per registered candidate on the formula engine, each effect leaving the mark it
// was measured to leave (synthetic_model.hpp, measured_marks), diagnosed with the local design.
// An effect whose mark reaches a calibration observation (so its parameter can be fitted) and a
// held-out one (so it predicts something) is the verdict, with its parameter; an effect without
// such a mark is never named, the report says which it lacks, and no twin names another effect.
// One with no mark at all is screened out before its runs and named invisible.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "orchestrator/diagnosis/pipeline/driver.hpp"
#include "orchestrator/diagnosis/report/report.hpp"
#include "synthetic_model.hpp"

namespace rockcal::diagnosis {
namespace {

using nlohmann::json;

// What the effect's measured mark lets the diagnosis do.
enum class Mark {
  named,             // on calibration and held-out observations: the verdict, with its parameter
  calibration_only,  // fixed by the calibration observations, predicts nothing held out
  held_out_only,     // seen on held-out observations only: nothing fixes its parameter
  absorbed,          // nothing the re-fitted strengths leave: screened out, named invisible
};

struct RegisteredTwin {
  const char* effect;
  Mark mark;
};

class RegisteredEffectTwin : public ::testing::TestWithParam<RegisteredTwin> {};

// Three quarters of the way to the effect's "strong" value: inside the walk, so the fit of its
// parameter is not held by a bound.
constexpr double kHiddenS = 0.75;

json diagnose_registered(const std::string& effect, double s) {
  DiagnosisCampaign c = testing::registry_twin_campaign(effect, s);
  c.grid.design = Design::local;
  c.grid.fr0 = c.grid.fs0 = 3;
  testing::SyntheticModel model(c.targets);
  model.marks = testing::measured_marks();
  return to_json(run_diagnosis(c, model), c);
}

TEST_P(RegisteredEffectTwin, IsNamedOnlyWhenItsMarkIsResolved) {
  const RegisteredTwin twin = GetParam();
  const json summary = diagnose_registered(twin.effect, kHiddenS);
  const json& v = summary["verdict"];
  std::printf("%s at s = %.2f: verdict %s, held-out gap %.2f budgets, G %s\n", twin.effect,
              kHiddenS, v["label"].get<std::string>().c_str(),
              summary["gap"]["held_out_budgets"].get<double>(), v["gap_closure"].dump().c_str());
  if (twin.mark == Mark::absorbed) {
    EXPECT_TRUE(v["effect"].is_null()) << v.dump(2);
    EXPECT_NE(summary["screen"]["reason"].get<std::string>().find(std::string(twin.effect) +
                                                                  " (its largest change"),
              std::string::npos)
        << summary["screen"].dump(2);
    for (const json& c : summary["candidates"]) EXPECT_NE(c["effect"], twin.effect);
    return;
  }
  if (twin.mark != Mark::named) {
    EXPECT_TRUE(v["effect"].is_null()) << v.dump(2);
    const json* mine = nullptr;
    for (const json& c : summary["candidates"]) {
      if (c["effect"] == twin.effect) mine = &c;
    }
    ASSERT_NE(mine, nullptr);
    const json& c = *mine;
    EXPECT_EQ(c["identifiable"].get<bool>(), twin.mark == Mark::calibration_only) << c.dump(2);
    EXPECT_EQ(c["moves"].empty(), twin.mark == Mark::absorbed) << c.dump(2);
    if (twin.mark == Mark::held_out_only) {
      // The user is told why, in the verdict and on the page.
      const std::string why = "only held-out observations: a calibration observation";
      EXPECT_NE(v["reason"].get<std::string>().find(why), std::string::npos) << v["reason"];
      EXPECT_NE(report_html(summary).find("moves only held-out observations"), std::string::npos);
    }
    return;
  }
  ASSERT_EQ(v["effect"], twin.effect) << v.dump(2);
  EXPECT_NEAR(v["parameter"]["s"].get<double>(), kHiddenS, 0.15) << v.dump(2);
  EXPECT_GE(v["gap_closure"].get<double>(), 0.6);
  EXPECT_TRUE(summary["gap"]["exceeds_budget"].get<bool>());
  EXPECT_NEAR(std::log(v["fr0"].get<double>() / 60), 0, 0.25);
  EXPECT_NEAR(std::log(v["fs0"].get<double>() / 120), 0, 0.25);
}

// Every registered effect has a row of marks: a new registration without one fails here.
TEST(RegisteredEffectTwins, EveryRegisteredEffectHasATwin) {
  const DiagnosisCampaign c = testing::registry_twin_campaign("", 0);
  EXPECT_EQ(c.candidates.size(), testing::measured_marks().size());
  for (const Candidate& k : c.candidates) {
    EXPECT_TRUE(testing::measured_marks().contains(k.effect)) << k.effect;
  }
}

TEST(RegisteredEffectTwins, TheNullTwinNamesNoEffect) {
  const json summary = diagnose_registered("", 0);
  EXPECT_TRUE(summary["verdict"]["effect"].is_null()) << summary["verdict"].dump(2);
  EXPECT_FALSE(summary["gap"]["exceeds_budget"].get<bool>()) << summary["gap"].dump(2);
  // The three effects without a measured mark are the screen's invisible ones, in registry order.
  EXPECT_EQ(summary["screen"]["invisible"],
            json::array({"platen_friction", "rolling_resistance", "brazilian_flats"}))
      << summary["screen"].dump(2);
}

INSTANTIATE_TEST_SUITE_P(
    MeasuredMarks, RegisteredEffectTwin,
    ::testing::Values(RegisteredTwin{"packing", Mark::named}, RegisteredTwin{"rate", Mark::named},
                      RegisteredTwin{"compression_coupling", Mark::named},
                      RegisteredTwin{"interaction_range", Mark::named},
                      RegisteredTwin{"flaws", Mark::calibration_only},
                      RegisteredTwin{"heterogeneity", Mark::held_out_only},
                      RegisteredTwin{"post_break_friction", Mark::held_out_only},
                      RegisteredTwin{"rolling_resistance", Mark::absorbed},
                      RegisteredTwin{"brazilian_flats", Mark::absorbed},
                      RegisteredTwin{"platen_friction", Mark::absorbed}),
    [](const auto& info) { return std::string(info.param.effect); });

}  // namespace
}  // namespace rockcal::diagnosis
