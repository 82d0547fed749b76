// Screening (orchestrator/diagnosis/analysis/screen.hpp): each effect run once at s = 1 at the base
// model's first fit, the strengths' re-fit removed, judged against budget + lab uncertainty. An
// effect that moves nothing beyond that is named invisible and gets no surfaces; one with a mark
// is kept and can still be the verdict; the null twin's verdict does not change.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "api/cli/diagnosis_text.hpp"
#include "orchestrator/diagnosis/analysis/screen.hpp"
#include "orchestrator/diagnosis/pipeline/driver.hpp"
#include "orchestrator/diagnosis/pipeline/grid.hpp"
#include "orchestrator/diagnosis/report/report.hpp"
#include "synthetic_model.hpp"

namespace rockcal::diagnosis {
namespace {

using nlohmann::json;
using testing::SyntheticModel;
using testing::twin_campaign;

RunOutcome run(std::vector<std::optional<double>> v) {
  return RunOutcome{std::move(v), ""};
}

std::vector<Target> three_targets() {
  std::vector<Target> t(3);
  const char* ids[] = {"uct-peak", "btt-peak", "uct-fast"};
  for (std::size_t i = 0; i < 3; ++i) {
    t[i].id = ids[i];
    t[i].sigma = 0.02;
    t[i].role = i < 2 ? Role::calibration : Role::held_out;
  }
  return t;
}

TEST(Screen, AMarkTheStrengthsAbsorbIsInvisibleAndOneTheyCannotIsNot) {
  // d ln / dz: target 0 on F_r0, 1 on F_s0, 2 on both; budget 0.01 each, noise 0.03.
  const std::vector<std::array<double, 2>> jacobian{{1.0, 0.0}, {0.0, 1.0}, {0.5, 0.5}};
  const std::vector<double> weight{2500, 2500, 0}, budget{0.01, 0.01, 0.01};
  const RunOutcome base = run({100.0, 50.0, 70.0});
  const double e = std::exp(0.2);
  // Every value up by e^0.2: a change of both strengths, nothing left once they are re-fitted.
  const ScreenedEffect absorbed = screen_effect("uniform", base, run({100 * e, 50 * e, 70 * e}),
                                                jacobian, weight, three_targets(), budget);
  EXPECT_FALSE(absorbed.visible);
  EXPECT_LT(absorbed.largest_in_noise, 1e-9);
  EXPECT_NEAR(absorbed.noise[2], 0.03, 1e-12);
  // The held-out value moves by 0.1 beyond what the re-fit explains: 3.3 noise budgets.
  const ScreenedEffect marked =
      screen_effect("rate", base, run({100 * e, 50 * e, 70 * e * std::exp(0.1)}), jacobian, weight,
                    three_targets(), budget);
  EXPECT_TRUE(marked.visible);
  ASSERT_TRUE(marked.largest);
  EXPECT_EQ(*marked.largest, 2u);
  EXPECT_NEAR(marked.change[2], 0.1, 1e-12);
  EXPECT_NEAR(marked.largest_in_noise, 0.1 / 0.03, 1e-9);
  // A dropped effect near the threshold is named with its mark and how to design it anyway; one
  // far below it only by name.
  ScreenedEffect faint =
      screen_effect("rate", base, run({100 * e, 50 * e, 70 * e * std::exp(0.025)}), jacobian,
                    weight, three_targets(), budget);
  EXPECT_FALSE(faint.visible);
  EXPECT_EQ(screened_out_text({absorbed, marked, faint}, three_targets()),
            "not tried, as invisible to these tests (screen): uniform, rate; of these, rate moved "
            "uct-fast 0.83 of its noise at the base fit, near the threshold: data an effect "
            "raised put the base fit away from the strengths it would need, where its mark can be "
            "larger; a request with \"screen\": false designs it");
  ScreenedEffect faint_too = faint;
  faint_too.effect = "flaws";
  const std::string both = screened_out_text({faint, faint_too}, three_targets());
  EXPECT_NE(both.find("of these, rate moved uct-fast 0.83 of its noise at the base fit, flaws "
                      "moved uct-fast 0.83 of its noise at the base fit, near the threshold"),
            std::string::npos)
      << both;
  EXPECT_EQ(both.substr(both.size() - 12), "designs them") << both;
  EXPECT_EQ(screened_out_text({absorbed}, three_targets()),
            "not tried, as invisible to these tests (screen): uniform");
  EXPECT_EQ(screened_out_text({marked}, three_targets()), "");
  // A strong run without values cannot show that the effect moves nothing: it is kept.
  const ScreenedEffect failed =
      screen_effect("packing", base, run({std::nullopt, std::nullopt, std::nullopt}), jacobian,
                    weight, three_targets(), budget);
  EXPECT_TRUE(failed.visible);
  EXPECT_FALSE(failed.largest);
}

// Focus: where the effect's design is centred, on the effect's own sensitivity. The base run fits
// the lab; the effect at s = 1 raises the first calibration peak by 0.2 and the second by 0.1 in
// ln. Its peaks answer the strengths the other way round from the base's (the first on F_s0, the
// second on F_r0, as a random packing's tension-controlled peaks against the FCC's), measured by
// one run a step along each: the strengths undo the change by moving -0.1 along F_r0 and -0.2
// along F_s0 (the base's sensitivity would say -0.2 and -0.1).
TEST(Screen, TheStrongRunsReFitOnItsOwnSensitivitySaysWhereTheEffectFits) {
  const std::vector<double> weight{2500, 2500, 0};
  std::vector<Target> targets = three_targets();
  const double lab[] = {100.0, 50.0, 70.0};
  for (std::size_t i = 0; i < 3; ++i) targets[i].value = lab[i];
  const double a = 100 * std::exp(0.2), b = 50 * std::exp(0.1), h = 0.05;
  const RunOutcome strong = run({a, b, 90.0});
  // A step h along F_r0 moves the second peak by h, along F_s0 the first.
  const std::vector<std::array<double, 2>> own = secant_jacobian(
      strong, {run({a, b * std::exp(h), 90.0}), run({a * std::exp(h), b, 90.0})}, {h, h});
  EXPECT_NEAR(own[0][0], 0.0, 1e-12);
  EXPECT_NEAR(own[0][1], 1.0, 1e-9);
  EXPECT_NEAR(own[1][0], 1.0, 1e-9);
  const std::array<double, 2> shift = fit_shift(strong, targets, own, weight);
  EXPECT_NEAR(shift[0], -0.1, 1e-9);
  EXPECT_NEAR(shift[1], -0.2, 1e-9);
  // A step whose run gave no value leaves no sensitivity: with none, the fit stays at the point.
  const std::vector<std::array<double, 2>> none =
      secant_jacobian(strong,
                      {run({std::nullopt, std::nullopt, std::nullopt}),
                       run({std::nullopt, std::nullopt, std::nullopt})},
                      {h, h});
  EXPECT_TRUE(std::isnan(none[0][0]));
  EXPECT_EQ(fit_shift(strong, targets, none, weight), (std::array<double, 2>{0.0, 0.0}));
}

struct Diagnosed {
  DiagnosisCampaign campaign;
  DiagnosisResult report;
  json summary;
  int runs = 0;
};

Diagnosed diagnose(const std::string& effect, double s, bool screen) {
  Diagnosed r{twin_campaign(effect, s), {}, {}, 0};
  r.campaign.screen = screen;
  SyntheticModel model(r.campaign.targets);
  r.report = run_diagnosis(r.campaign, model);
  r.summary = to_json(r.report, r.campaign);
  r.runs = model.runs;
  return r;
}

std::vector<std::string> effects_of(const json& summary) {
  std::vector<std::string> out;
  for (const json& c : summary["candidates"]) {
    if (!c["effect"].is_null()) out.push_back(c["effect"]);
  }
  return out;
}

// The sentence the report prints, rebuilt from the screen's own fields.
std::string screen_reason_from_fields(const json& screen) {
  std::string named;
  char line[256];
  for (const json& e : screen["effects"]) {
    if (e["visible"].get<bool>()) continue;
    const json& l = e["largest"];
    std::snprintf(line, sizeof line,
                  " (its largest change %.2f of its noise, on %s: %+.3f in ln, noise %.3f)",
                  l["in_noise"].get<double>(), l["id"].get<std::string>().c_str(),
                  l["change"].get<double>(), l["noise"].get<double>());
    named += (named.empty() ? "" : ", ") + e["effect"].get<std::string>() + line;
  }
  std::snprintf(line, sizeof line, "at the base fit (F_r0 %.3g N, F_s0 %.3g N)",
                screen["point"]["fr0"].get<double>(), screen["point"]["fs0"].get<double>());
  std::string where = line;
  if (!screen["balanced_point"].is_null()) {
    std::snprintf(line, sizeof line,
                  " and at the balanced point (F_r0 %.3g N, F_s0 %.3g N: equal strengths at their "
                  "geometric mean, within the box)",
                  screen["balanced_point"]["fr0"].get<double>(),
                  screen["balanced_point"]["fs0"].get<double>());
    where += line;
  }
  return "invisible to these tests: " + named +
         ": at its strong value (s = 1), with the strengths re-fitted, each moves no observation "
         "beyond its noise (budget + lab uncertainty) " +
         where + ", so it was not designed further (" +
         std::to_string(screen["skipped_model_points"].get<int>()) +
         " model points of surfaces not run)";
}

TEST(Screen, AnEffectThatLeavesNoMarkIsNamedInvisibleAndNotDesigned) {
  // Hidden: size. "uniform" lowers every peak by one factor, which the strengths absorb.
  const Diagnosed on = diagnose("size", 0.8, true);
  const Diagnosed off = diagnose("size", 0.8, false);
  const json& screen = on.summary["screen"];
  EXPECT_TRUE(screen["enabled"].get<bool>());
  EXPECT_EQ(screen["invisible"], json::array({"uniform"})) << screen.dump(2);
  EXPECT_EQ(effects_of(on.summary),
            (std::vector<std::string>{"size", "confinement", "rate", "modulus"}));
  EXPECT_EQ(effects_of(off.summary),
            (std::vector<std::string>{"size", "confinement", "rate", "uniform", "modulus"}));
  // Judged at the base model's first fit, where the budget weighted the calibration.
  EXPECT_EQ(screen["point"]["fr0"], on.summary["budget"]["weights"]["point"]["fr0"]);
  for (const json& e : screen["effects"]) {
    const double in_noise = e["largest"]["in_noise"].get<double>();
    EXPECT_EQ(e["visible"].get<bool>(), in_noise > 1.0) << e.dump(2);
  }
  const std::string reason = screen_reason_from_fields(screen);
  EXPECT_EQ(screen["reason"], reason);
  EXPECT_NE(api::diagnosis_text(on.summary).find("Screen: " + reason + "\n"), std::string::npos);
  EXPECT_NE(report_html(on.summary).find("<p>Screen: " + reason + "</p>"), std::string::npos);
  // The kept effect with the mark is still the verdict.
  EXPECT_EQ(on.summary["verdict"]["effect"], "size");
  EXPECT_EQ(off.summary["verdict"]["effect"], "size");
  // uniform's 2 x 16 grid points are not run; the screen ran three points per effect (15: its
  // strong run and a step along each strength).
  EXPECT_EQ(screen["skipped_model_points"], 32);
  EXPECT_EQ(screen["model_points"], 3 * 5);
  EXPECT_EQ(off.runs - on.runs, 32 - 3 * 5);
  EXPECT_EQ(off.summary["runs"]["model_points"].get<int>() -
                on.summary["runs"]["model_points"].get<int>(),
            32 - 3 * 5);
  EXPECT_EQ(off.summary["screen"]["reason"], "not screened (\"screen\": false)");
  std::printf("screen: %d model points without it, %d with it; %s\n", off.runs, on.runs,
              reason.c_str());
}

TEST(Screen, TheNullTwinSaysWhatItSaid) {
  const Diagnosed on = diagnose("", 0.0, true);
  const Diagnosed off = diagnose("", 0.0, false);
  for (const char* field : {"label", "reason", "effect"}) {
    EXPECT_EQ(on.summary["verdict"][field], off.summary["verdict"][field]) << field;
  }
  EXPECT_EQ(on.summary["verdict"]["label"], "no effect needed");
  EXPECT_EQ(on.summary["verdict"]["confidence"]["level"],
            off.summary["verdict"]["confidence"]["level"]);
  EXPECT_EQ(on.summary["screen"]["invisible"], json::array({"uniform"}));
}

// With every candidate invisible nothing is designed, and a gap left unexplained says why.
TEST(Screen, AGapWithEveryEffectInvisibleNamesThem) {
  Diagnosed r{twin_campaign("size", 0.8), {}, {}, 0};
  std::erase_if(r.campaign.candidates, [](const Candidate& k) { return k.effect != "uniform"; });
  SyntheticModel model(r.campaign.targets);
  r.report = run_diagnosis(r.campaign, model);
  r.summary = to_json(r.report, r.campaign);
  EXPECT_EQ(r.summary["candidates"].size(), 1u);
  EXPECT_TRUE(r.summary["gap"]["exceeds_budget"].get<bool>());
  const std::string reason = r.summary["verdict"]["reason"];
  // Its mark, from the screen's fields: near the threshold (the re-fit's error reached 0.71 of the
  // noise on a generic x86-64 build's round-off) the tail says so and how to design it anyway.
  const json& largest = r.summary["screen"]["effects"][0]["largest"];
  std::string tail = "; not tried, as invisible to these tests (screen): uniform";
  if (largest["in_noise"].get<double>() >= kScreenNearThreshold) {
    char mark[128];
    std::snprintf(mark, sizeof mark,
                  "; of these, uniform moved %s %.2f of its noise at the base fit",
                  largest["id"].get<std::string>().c_str(), largest["in_noise"].get<double>());
    tail += std::string(mark) +
            ", near the threshold: data an effect raised put the base fit away from the strengths "
            "it would need, where its mark can be larger; a request with \"screen\": false "
            "designs it";
  }
  ASSERT_GE(reason.size(), tail.size());
  EXPECT_EQ(reason.substr(reason.size() - tail.size()), tail) << reason;
  std::printf("every effect invisible: %s\n", reason.c_str());
  EXPECT_EQ(r.summary["gap"]["closure_missing"],
            "the screen found every candidate effect invisible to these tests (screen.reason): "
            "the diagnosis only locates the gap");
}

// Focus: an effect whose mark depends on where the strengths lie. "fading" (synthetic_model.hpp)
// moves the confined peaks only where F_s0 is not well above F_r0: at the twin's fit (F_s0 = 2
// F_r0) it leaves 3% of its mark, below the noise; at equal strengths 89%. The screen looks there
// too, keeps it, says where it saw it, and centres its design on its fit from there.
TEST(Screen, AnEffectWithoutAMarkAtTheBaseFitButOneAtEqualStrengthsIsKept) {
  Diagnosed r{twin_campaign("", 0.0), {}, {}, 0};
  // A box of x8 puts the balanced point (84.9 N) 0.17 of it from the truth's strengths, beyond a
  // grid step and a half (the default box's x16 leaves 0.125: no second point).
  r.campaign.fr0_n = {30, 240};
  r.campaign.fs0_n = {30, 240};
  std::erase_if(r.campaign.candidates, [](const Candidate& k) { return k.effect != "uniform"; });
  r.campaign.candidates.push_back({"fading", "s", "", [](double s) { return s; }});
  SyntheticModel model(r.campaign.targets);
  r.report = run_diagnosis(r.campaign, model);
  r.summary = to_json(r.report, r.campaign);
  const json& screen = r.summary["screen"];
  ASSERT_FALSE(screen["balanced_point"].is_null()) << screen.dump(2);
  const double fr0 = screen["point"]["fr0"], fs0 = screen["point"]["fs0"];
  EXPECT_NEAR(screen["balanced_point"]["fr0"].get<double>(), std::sqrt(fr0 * fs0), 1e-9 * fr0);
  EXPECT_EQ(screen["balanced_point"]["fr0"], screen["balanced_point"]["fs0"]);
  const json& uniform = screen["effects"][0];
  const json& fading = screen["effects"][1];
  EXPECT_FALSE(uniform["visible"].get<bool>());
  EXPECT_EQ(uniform["judged_at"], "base fit");
  EXPECT_TRUE(fading["visible"].get<bool>()) << fading.dump(2);
  EXPECT_EQ(fading["judged_at"], "balanced point");
  EXPECT_EQ(fading["largest"]["id"].get<std::string>().substr(0, 4), "tri-");  // confined
  EXPECT_GT(fading["largest"]["in_noise"].get<double>(), 1.0);
  EXPECT_EQ(effects_of(r.summary), (std::vector<std::string>{"fading"}));
  // Both points' runs: three per effect at each, and the base's at the second.
  EXPECT_EQ(screen["model_points"], 2 * 3 * 2 + 1);
  EXPECT_EQ(screen["reason"],
            screen_reason_from_fields(screen) +
                "; fading: no mark at the base fit but one at the balanced point, "
                "so designed around its fit from there");
  // Hidden: none. The kept effect is not the verdict.
  EXPECT_TRUE(r.summary["verdict"]["effect"].is_null());
  // The next test marks it where the screen saw it: its run and the base's three at the balanced
  // point.
  const json& balanced = screen["balanced_point"];
  int fading_runs = 0, base_runs = 0;
  for (const json& run : r.summary["next_test"]["runs"]) {
    if (run["fr0"] != balanced["fr0"] || run["fs0"] != balanced["fs0"]) continue;
    (run["effect"] == "fading" ? fading_runs : base_runs) += 1;
  }
  EXPECT_EQ(fading_runs, 1) << r.summary["next_test"].dump(2);
  EXPECT_EQ(base_runs, 1);  // and two a step away
  // The base's three at the fit, the two effects', the base's three at the balanced point and the
  // base at the fit under the budget's 4 variants.
  EXPECT_EQ(r.summary["next_test"]["runs"].size(), 3u + 2u + 3u + 4u);
  std::printf("%s\n", screen["reason"].get<std::string>().c_str());
}

}  // namespace
}  // namespace rockcal::diagnosis
