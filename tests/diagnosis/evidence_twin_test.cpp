// Focus: the evidence threshold (DecisionRule::min_evidence) on twins of the formula engine that
// leave each registered effect's measured mark (synthetic_model.hpp), lab noise as large as the
// stated 2% uncertainty. Null twins (no hidden effect) put a contender above the default
// threshold at most 10% of the time, and twins hiding an effect at the detection limit (s = 0.2 of
// its walk, where every nameable effect was named in 15 of 15 twins) are named, that effect
// first. ROCKCAL_NULL_TWINS=N runs N null twins instead of 20 (docs/diagnosis-measurements.md).
// The report's evidence (each candidate's lpd term by term, the verdict's sentence, the page and
// the CLI) is rebuilt from its own fields.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>

#include "api/cli/diagnosis_text.hpp"
#include "orchestrator/diagnosis/pipeline/driver.hpp"
#include "orchestrator/diagnosis/report/report.hpp"
#include "synthetic_model.hpp"

namespace rockcal::diagnosis {
namespace {

using nlohmann::json;

constexpr double kLabNoise = 0.02;  // the twins' stated uncertainty: the lab is as noisy as it says

// The nominal verdict only: the bootstrap (its confidence) does not change which effect is named.
json diagnose(const std::string& effect, double s, std::uint64_t seed) {
  DiagnosisCampaign c = testing::registry_twin_campaign(effect, s, kLabNoise, seed);
  c.grid.design = Design::local;
  c.grid.fr0 = c.grid.fs0 = 3;
  c.bootstrap = 0;
  testing::SyntheticModel model(c.targets);
  model.marks = testing::measured_marks();
  return to_json(run_diagnosis(c, model), c);
}

int null_twins() {
  const char* n = std::getenv("ROCKCAL_NULL_TWINS");
  return n ? std::max(12, std::atoi(n)) : 20;
}

TEST(EvidenceThreshold, AtMostOneNullTwinInTenNamesAnEffect) {
  const int twins = null_twins();
  const double threshold = DecisionRule{}.min_evidence;
  std::vector<double> best;  // each null's best contender's evidence
  int named = 0;
  for (int seed = 1; seed <= twins; ++seed) {
    const json v = diagnose("", 0, seed)["verdict"];
    const json& e = v["evidence"];
    EXPECT_EQ(e["threshold"], threshold);
    if (!e["value"].is_number()) {
      // No contender: every confirmed effect was inert at its fitted value (its evidence the
      // strengths' re-fit) or none was confirmed; nothing can be named.
      EXPECT_FALSE(v["effect"].is_string()) << v.dump(2);
      best.push_back(-std::numeric_limits<double>::infinity());
      continue;
    }
    best.push_back(e["value"].get<double>());
    // Named exactly when the best contender's evidence exceeds the threshold, and then it is.
    EXPECT_EQ(v["effect"].is_string(), best.back() > threshold) << v.dump(2);
    if (v["effect"].is_string()) {
      ++named;
      EXPECT_EQ(v["effect"], e["effect"]);
    } else {
      // A null's base model may still miss beyond the rule by chance: then the label says so.
      EXPECT_EQ(v["label"], v["miss"].is_null() ? "no effect needed" : "unexplained miss");
    }
  }
  std::sort(best.begin(), best.end(), std::greater<>());
  // The threshold at most 10% of these nulls exceed (bench/diagnosis_confusion.py's rule).
  const double calibrated = best[std::size_t(0.1 * twins)];
  std::printf(
      "%d null twins: %d named at the default %.2f nats; best evidence %.2f, %.2f, %.2f; "
      "the threshold at most 10%% exceed: %.2f nats\n",
      twins, named, threshold, best[0], best[1], best[2], calibrated);
  EXPECT_LE(10 * named, twins) << named << " of " << twins << " nulls named an effect";
  EXPECT_GE(threshold, calibrated);
}

std::string two(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", x);
  return buf;
}

// Each term is -0.5 (r^2 / v + ln 2 pi v) of the observation's charged residual and its budget^2 +
// lab uncertainty^2 + the spread the fit leaves in the prediction (real runs: no emulator
// variance); an effect's evidence is its terms' sum less the base's.
void expect_terms_from_fields(const json& summary) {
  std::map<std::string, const json*> observation;
  for (const json& o : summary["observations"]) observation[o["id"]] = &o;
  std::map<std::string, double> base;
  for (const json& c : summary["candidates"]) {
    const json& e = c["evidence"];
    if (e.is_null() || e["basis"] != "confirmed") continue;
    double lpd = 0, over_base = 0;
    for (const json& t : e["terms"]) {
      const json& o = *observation.at(t["id"]);
      EXPECT_EQ(o["role"], "held_out");
      const double spread = t["prediction_variance"].get<double>();
      EXPECT_GE(spread, 0.0);
      const double v = std::pow(o["budget"].get<double>(), 2) +
                       std::pow(o["lab_uncertainty"].get<double>(), 2) + spread;
      const double r = t["charged"].get<double>();
      EXPECT_NEAR(t["variance"].get<double>(), v, 1e-12 * v);
      EXPECT_NEAR(t["lpd"].get<double>(), -0.5 * (r * r / v + std::log(2 * M_PI * v)), 1e-9);
      lpd += t["lpd"].get<double>();
      if (c["effect"].is_null()) {
        EXPECT_EQ(r, o["base"]["charged"].get<double>());
        base[t["id"]] = t["lpd"].get<double>();
      } else {
        over_base += t["lpd"].get<double>() - base.at(t["id"]);
      }
    }
    EXPECT_NEAR(e["lpd"].get<double>(), lpd, 1e-9);
    if (c["effect"].is_string()) {
      EXPECT_NEAR(e["value"].get<double>(), over_base, 1e-9);
    }
  }
}

TEST(EvidenceReport, TheVerdictSentenceAndTheTermsAreTheReportsFields) {
  const json named = diagnose("compression_coupling", 0.2, 1);
  expect_terms_from_fields(named);
  const json& v = named["verdict"];
  const std::string threshold = two(v["evidence"]["threshold"].get<double>());
  const std::string evidence = two(v["evidence"]["value"].get<double>());
  EXPECT_EQ(threshold, "1.00");
  EXPECT_EQ(v["reason"].get<std::string>().rfind(
                "compression_coupling: evidence " + evidence +
                    " nats over the base (threshold 1.00); it closes G = " +
                    two(v["gap_closure"].get<double>()) + " of the held-out gap",
                0),
            0u)
      << v["reason"];
  EXPECT_EQ(named["decision"]["min_evidence"], 1.0);
  const std::string html = report_html(named);
  EXPECT_NE(html.find("<h2>Evidence per effect</h2>"), std::string::npos);
  EXPECT_NE(
      html.find("compression_coupling: " + evidence + " nats over the base; threshold 1.00 nats"),
      std::string::npos);
  EXPECT_NE(api::diagnosis_text(named).find("evidence " + evidence + " nats (threshold 1.00)"),
            std::string::npos);

  // Nothing named: the sentence gives the best contender's evidence against the threshold, and
  // each confirmed effect inert at its fitted value with its evidence and its mark there.
  const json null = diagnose("", 0, 1);
  expect_terms_from_fields(null);
  const json& n = null["verdict"];
  const std::string reason = n["reason"].get<std::string>();
  if (n["evidence"]["value"].is_number()) {
    const std::string best = n["evidence"]["effect"].get<std::string>();
    EXPECT_NE(reason.find("no gap to explain; the best effect, " + best + ", has evidence " +
                          two(n["evidence"]["value"].get<double>()) +
                          " nats over the base (threshold 1.00)"),
              std::string::npos)
        << reason;
  }
  int inert = 0;
  for (const json& c : null["candidates"]) {
    if (!c["effect"].is_string() || !c["mark_at_fit"]["inert"].get<bool>()) continue;
    ++inert;
    EXPECT_NE(reason.find(c["effect"].get<std::string>() + " (evidence " +
                          two(c["evidence"]["value"].get<double>()) +
                          " nats) is not the explanation: at its fitted value it changes no "
                          "observation beyond its noise against the base model at the same "
                          "strengths (largest change " +
                          two(c["mark_at_fit"]["in_noise"].get<double>()) + " of its noise)"),
              std::string::npos)
        << reason;
  }
  EXPECT_TRUE(inert > 0 || n["evidence"]["value"].is_number()) << reason;
}

class EffectAtTheDetectionLimit : public ::testing::TestWithParam<const char*> {};

TEST_P(EffectAtTheDetectionLimit, IsNamedFirst) {
  const std::string effect = GetParam();
  const DecisionRule rule;
  int named = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const json summary = diagnose(effect, 0.2, seed);
    const json& v = summary["verdict"];
    for (const json& c : summary["candidates"]) {
      if (c["rank"] == 1) {
        EXPECT_EQ(c["effect"], effect) << "seed " << seed;
      }
    }
    // At the limit the base model's held-out gap can fall within the rule's budgets (0.98 on a
    // generic x86-64 build's round-off for rate): then nothing is named, and the reason says the
    // best effect had evidence but no gap to explain.
    const double gap = summary["gap"]["held_out_budgets"].get<double>();
    if (gap > rule.gap_budgets) {
      EXPECT_EQ(v["effect"], effect) << "seed " << seed << "\n" << v.dump(2);
      EXPECT_GT(v["evidence"]["value"].get<double>(), rule.min_evidence);
      named += v["effect"] == effect ? 1 : 0;
    } else {
      EXPECT_TRUE(v["effect"].is_null()) << v.dump(2);
      EXPECT_NE(
          v["reason"].get<std::string>().find("no gap to explain; the best effect, " + effect),
          std::string::npos)
          << v.dump(2);
    }
    // interaction_range has no weaker version than its first change in FCC: hidden there.
    std::printf("%s at s = %.3g, seed %d: %s, held-out gap %.2f budgets\n", effect.c_str(),
                testing::hidden_s(effect, 0.2), int(seed), v["label"].get<std::string>().c_str(),
                gap);
  }
  // Rate's gaps here are 1.01, 1.03 and 1.44 budgets (1.01, 0.98, 1.40 on the generic build): at
  // the limit, so one seed named is what holds on any round-off.
  EXPECT_GE(named, 1) << "named where its gap is seen";
}

// The effects whose measured mark reaches a calibration and a held-out observation
// (candidate_twin_test.cpp): rate's through the fast disc (calibration) and the fast UCT.
INSTANTIATE_TEST_SUITE_P(MeasuredMarks, EffectAtTheDetectionLimit,
                         ::testing::Values("packing", "compression_coupling", "interaction_range",
                                           "rate"),
                         [](const auto& info) { return std::string(info.param); });

// On demand (--gtest_also_run_disabled_tests; ROCKCAL_SHARE_TWINS=N seeds a value, at least 5,
// default 10): the share of twins named top-1 per effect at s = 0.05, 0.1, 0.15 and 0.2, and the
// detection limit, the smallest of those named in >= 80% (docs/diagnosis-measurements.md). What it
// asserts is the default suite's claim above on N seeds: at s = 0.2 each effect is named in at
// least 80% of its twins.
TEST(EffectShares, DISABLED_AtTheDetectionLimitEachEffectIsNamedInFourOfFive) {
  const char* n = std::getenv("ROCKCAL_SHARE_TWINS");
  const int seeds = n ? std::max(5, std::atoi(n)) : 10;
  for (const char* effect : {"rate", "compression_coupling", "packing", "interaction_range"}) {
    std::string row = effect, limit = "none";
    for (double s : {0.05, 0.1, 0.15, 0.2}) {
      int named = 0, other = 0;
      for (int seed = 1; seed <= seeds; ++seed) {
        const json v = diagnose(effect, s, std::uint64_t(seed))["verdict"];
        named += v["effect"] == effect;
        other += v["effect"].is_string() && v["effect"] != effect;
      }
      row += " | " + std::to_string(named) + "/" + std::to_string(seeds) +
             (other ? " (" + std::to_string(other) + " another)" : "");
      if (limit == "none" && 5 * named >= 4 * seeds) limit = "s = " + two(s);
      if (s == 0.2) {
        EXPECT_GE(5 * named, 4 * seeds) << effect << ": " << named << " of " << seeds;
      }
    }
    std::printf("| %s | %s |\n", row.c_str(), limit.c_str());
  }
}

}  // namespace
}  // namespace rockcal::diagnosis
