// Focus: data that disagree with themselves. Two observations under nearly the same conditions
// (consistency.hpp's tolerances) whose values differ beyond their stated uncertainties are named
// with the size of the disagreement, and a model is charged only beyond the span of their values:
// on the formula engine a second lab's UCT 20% above the first is no gap of the model, while the
// same value under other conditions is one; a pair that agrees is not flagged.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "orchestrator/diagnosis/analysis/consistency.hpp"
#include "orchestrator/diagnosis/analysis/gap.hpp"
#include "orchestrator/diagnosis/pipeline/driver.hpp"
#include "orchestrator/diagnosis/report/report.hpp"
#include "synthetic_model.hpp"

namespace rockcal::diagnosis {
namespace {

using nlohmann::json;

Target uct(const std::string& id, double value, double uncertainty, Role role = Role::held_out) {
  Target t;
  t.id = id;
  t.role = role;
  t.conditions.test = TestKind::uct;
  t.conditions.diameter_m = 10;
  t.conditions.height_m = 20;
  t.conditions.platen_velocity_m_s = 0.05;
  t.value = value;
  t.sigma = uncertainty / value;
  return t;
}

// Two labs' UCT of one specimen: 1,000 +- 20 and 1,200 +- 24 differ by ln 1.2 = 6.4 combined sd.
TEST(DataConsistency, ADisagreeingPairIsNamedWithItsSize) {
  const std::vector<Target> t = {uct("uct-1", 1000, 20), uct("uct-2", 1200, 24)};
  const std::vector<Inconsistency> pairs = find_inconsistencies(t);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0].first, 0u);
  EXPECT_EQ(pairs[0].second, 1u);
  EXPECT_NEAR(pairs[0].ln_difference, std::log(1.2), 1e-12);
  EXPECT_NEAR(pairs[0].sigmas, std::log(1.2) / std::hypot(0.02, 0.02), 1e-9);
  EXPECT_EQ(inconsistency_text(pairs, t),
            "uct-1 and uct-2 (uct peak_load, nearly the same conditions) differ by +20% in value, "
            "6.4 times their combined uncertainty");
}

// 1,000 +- 20 and 1,030 +- 20.6 (1.1 sd) agree; so does any pair under other conditions, however
// far apart: another height, another confinement, a peak load 2% wider (beyond its 1%), and a
// strength 6% wider (beyond its 5%). A strength 4% wider is nearly the same specimen.
TEST(DataConsistency, APairThatAgreesOrDiffersInConditionsIsNotFlagged) {
  EXPECT_TRUE(find_inconsistencies({uct("uct-1", 1000, 20), uct("uct-2", 1030, 20.6)}).empty());
  Target taller = uct("uct-tall", 2000, 40);
  taller.conditions.height_m = 24;
  EXPECT_TRUE(find_inconsistencies({uct("uct-1", 1000, 20), taller}).empty());
  Target confined = uct("tri", 2000, 40);
  confined.conditions.test = TestKind::triaxial;
  Target confined_more = confined;
  confined_more.conditions.confining_pressure_pa = 1.0;
  confined.conditions.confining_pressure_pa = 1.1;
  confined_more.value = 1000;
  EXPECT_TRUE(find_inconsistencies({confined, confined_more}).empty());
  Target wider = uct("uct-wide", 2000, 40);
  wider.conditions.diameter_m = 10.2;
  EXPECT_TRUE(find_inconsistencies({uct("uct-1", 1000, 20), wider}).empty());

  Target strength = uct("ucs-1", 100e6, 2e6);
  strength.observable = Observable::strength;
  Target other_lab = strength;
  other_lab.id = "ucs-2";
  other_lab.value = 120e6;
  other_lab.conditions.diameter_m = 10.6;
  EXPECT_TRUE(find_inconsistencies({strength, other_lab}).empty());
  other_lab.conditions.diameter_m = 10.4;
  EXPECT_EQ(find_inconsistencies({strength, other_lab}).size(), 1u);
}

// A residual inside the pair's span is not charged; outside it, only its distance to the nearer
// value is. An observation in no pair is charged its whole residual.
TEST(DataConsistency, AModelIsChargedOnlyBeyondThePairsSpan) {
  const std::vector<Target> t = {uct("uct-1", 1000, 20), uct("uct-2", 1200, 24),
                                 uct("uct-3", 500, 10)};
  const double l12 = std::log(1.2);
  std::vector<Target> apart = t;
  apart[2].conditions.height_m = 30;  // another test: no pair with the first two
  // A model at 1,100 (between the two labs): nothing charged on either.
  const double between = std::log(1100.0);
  std::vector<double> r = {between - std::log(1000.0), between - std::log(1200.0), 0.3};
  std::vector<double> charged = charged_residuals(r, apart);
  EXPECT_EQ(charged[0], 0.0);
  EXPECT_EQ(charged[1], 0.0);
  EXPECT_EQ(charged[2], 0.3);
  // A model at 500: both charged their distance to 1,000, the nearer value.
  r = {std::log(0.5), std::log(500.0 / 1200), 0.0};
  charged = charged_residuals(r, apart);
  EXPECT_NEAR(charged[0], std::log(0.5), 1e-12);
  EXPECT_NEAR(charged[1], std::log(0.5), 1e-12);
  // Above both: charged its distance to 1,200.
  r = {std::log(1.5), std::log(1.5) - l12, 0.0};
  charged = charged_residuals(r, apart);
  EXPECT_NEAR(charged[0], std::log(1.5) - l12, 1e-12);
  EXPECT_NEAR(charged[1], std::log(1.5) - l12, 1e-12);
}

// The formula engine's null twin with a second lab's UCT of the calibration specimen, held out,
// 20% above the first (2% each: 6.4 combined sd). It is named, not charged: no gap, "no effect
// needed". The same value on a UCT of another height is a gap the model is charged with.
TEST(DataConsistency, AnInconsistentPairIsNotChargedAsAGap) {
  DiagnosisCampaign c = testing::twin_campaign("", 0.0);
  Target second = c.targets[0];  // uct-peak, calibration
  ASSERT_EQ(second.id, "uct-peak");
  second.id = "uct-peak-lab2";
  second.role = Role::held_out;
  second.value *= 1.2;
  c.targets.push_back(second);
  testing::SyntheticModel model(c.targets);
  const json s = to_json(run_diagnosis(c, model), c);
  ASSERT_EQ(s["data_inconsistencies"].size(), 1u) << s["data_inconsistencies"].dump();
  EXPECT_EQ(s["data_inconsistencies"][0]["first"], "uct-peak");
  EXPECT_EQ(s["data_inconsistencies"][0]["second"], "uct-peak-lab2");
  const std::string reason = s["verdict"]["reason"];
  const char* clause =
      "; the data disagree with themselves: uct-peak and uct-peak-lab2 (uct peak_load, nearly the "
      "same conditions) differ by +20% in value, 6.4 times their combined uncertainty: no model "
      "meets both, so only a residual beyond the span of their values is charged to the model";
  ASSERT_GE(reason.size(), std::strlen(clause));
  EXPECT_EQ(reason.substr(reason.size() - std::strlen(clause)), clause) << reason;
  EXPECT_EQ(s["verdict"]["label"], "no effect needed") << reason;
  EXPECT_FALSE(s["gap"]["exceeds_budget"].get<bool>()) << s["gap"].dump();
  const json& lab2 = s["observations"].back();
  EXPECT_GT(std::abs(lab2["base"]["residual"].get<double>()), 0.1);  // its raw residual
  EXPECT_EQ(lab2["base"]["charged"], 0.0);
  for (const json& id : s["gap"]["significant"]) EXPECT_NE(id, "uct-peak-lab2");

  DiagnosisCampaign apart = c;
  apart.targets.back().conditions.height_m *= 1.1;  // another test: its own run, its own value
  testing::SyntheticModel other(apart.targets);
  const json a = to_json(run_diagnosis(apart, other), apart);
  EXPECT_TRUE(a["data_inconsistencies"].empty());
  EXPECT_TRUE(a["gap"]["exceeds_budget"].get<bool>()) << a["gap"].dump();
  EXPECT_EQ(a["gap"]["significant"], json::array({"uct-peak-lab2"}));
}

}  // namespace
}  // namespace rockcal::diagnosis
