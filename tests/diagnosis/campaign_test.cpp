// A diagnosis request is validated whole before anything runs, and every refusal names the field
// to change; a good request resolves into model-unit targets and registry candidates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include "engine/effects/effect.hpp"
#include "orchestrator/diagnosis/analysis/budget.hpp"
#include "orchestrator/diagnosis/analysis/trust_region.hpp"
#include "orchestrator/diagnosis/diagnosis_kind.hpp"
#include "orchestrator/diagnosis/pipeline/campaign.hpp"
#include "orchestrator/diagnosis/pipeline/grid.hpp"
#include "orchestrator/diagnosis/pipeline/jobs.hpp"

namespace rockcal::diagnosis {
namespace {

using nlohmann::json;

json observation(const std::string& id, const std::string& test, const std::string& role,
                 json conditions = json::object()) {
  return {{"id", id},
          {"test", test},
          {"conditions", conditions},
          {"observable", "peak_load"},
          {"value", 1000.0},
          {"uncertainty", 20.0},
          {"role", role}};
}

json request() {
  json observations = json::array();
  observations.push_back(observation("uct", "uct", "calibration"));
  observations.push_back(observation("btt", "btt", "calibration"));
  observations.push_back(observation("tri", "triaxial", "held_out", {{"confining_pressure", 50}}));
  observations.push_back(
      observation("uct-big", "uct", "held_out", {{"diameter", 9}, {"height", 18}}));
  json r;
  r["kind"] = "diagnosis";
  r["name"] = "validation";
  r["job"] = {{"sample", {{"diameter", 6}, {"height", 12}, {"radius", 1}}},
              {"material", {{"kr", 8000}, {"nu", 0.2}, {"density", 1}}},
              {"loading", {{"platen_velocity", 0.05}, {"max_strain", 0.3}}}};
  r["dataset"] = {{"name", "small"}, {"units", "model"}, {"observations", observations}};
  r["effects"] = {"heterogeneity", "platen_friction"};
  r["bounds"] = {{"fr0", {16, 256}}, {"fs0", {16, 256}}};
  r["grid"] = {{"fr0", 3}, {"fs0", 3}, {"s", 3}};
  return r;
}

std::string refused_field(const json& r) {
  try {
    parse_diagnosis_campaign(r);
  } catch (const orch::RequestError& e) {
    return e.field;
  }
  return "(accepted)";
}

TEST(DiagnosisRequest, GoodRequestResolves) {
  const DiagnosisCampaign c = parse_diagnosis_campaign(request());
  ASSERT_EQ(c.targets.size(), 4u);
  EXPECT_EQ(c.targets[0].conditions.diameter_m, 6);   // absent: the template's
  EXPECT_EQ(c.targets[1].conditions.thickness_m, 3);  // the engine's D/2
  EXPECT_EQ(c.targets[3].conditions.diameter_m, 9);
  EXPECT_NEAR(c.targets[0].sigma, 0.02, 1e-12);
  ASSERT_EQ(c.candidates.size(), 2u);
  EXPECT_EQ(c.candidates[0].effect, "heterogeneity");
  EXPECT_EQ(c.budget.seeds, (std::vector<std::uint64_t>{2, 3, 4, 5}));
  // 4 distinct runs; 9 + 2 x 18 grid points, 5 x 7 budget points at most twice (the first and
  // the confirmed fit) and the screen's 3 points per effect at each of its two points and the
  // base's at the second, 3 confirmed candidates x (3 refinement runs + 4 seeds) and the base
  // model at each confirmed effect's strengths; and the next test's base at its fit and two steps
  // (and at the screen's balanced point), both effects and the base at its fit under the budget's 6
  // variants (4 seeds, half speed, 1.25x) on the dataset's 4 runs and the menu's 9 more (squat and
  // slender UCT, two discs, a fast UCT and disc, three triaxials; the UCT's modulus and peak strain
  // are read off the dataset's UCT run).
  constexpr int kNextTest = (2 * 3 + 2 + 6) * (4 + 9);
  constexpr int kScreen = 1 + 2 * 3 * 2;
  EXPECT_EQ(planned_jobs(c), (9 + 2 * 18 + 2 * 5 * 7 + kScreen + 3 * 7 + 2) * 4u + kNextTest);
  // The progress model's budget names them by phase.
  const std::vector<orch::BudgetPart> parts = planned_job_parts(c);
  ASSERT_EQ(parts.size(), 4u);
  EXPECT_EQ(parts[0].name, "grid");
  EXPECT_EQ(parts[0].budget, (9 + 2 * 18) * 4);
  EXPECT_EQ(parts[1].name, "budget");
  EXPECT_EQ(parts[1].budget, (2 * 5 * 7 + kScreen) * 4);
  EXPECT_EQ(parts[2].name, "confirm");
  EXPECT_EQ(parts[2].budget, (3 * 7 + 2) * 4);
  EXPECT_EQ(parts[3].name, "next_test");
  EXPECT_EQ(parts[3].budget, kNextTest);
  EXPECT_EQ(c.budget.resolutions, std::vector<double>{1.25});
  // Two resolutions: one more run at each budget point.
  json two = request();
  two["budget"] = {{"resolution", {1.25, 1.5}}};
  const DiagnosisCampaign c2 = parse_diagnosis_campaign(two);
  EXPECT_EQ(c2.budget.resolutions, (std::vector<double>{1.25, 1.5}));
  EXPECT_EQ(planned_jobs(c2),
            (9 + 2 * 18 + 2 * 5 * 8 + kScreen + 3 * 7 + 2) * 4u + kNextTest + (4 + 9));
  EXPECT_EQ(budget_runs_per_point(c2.budget), 8u);  // reference, 4 seeds, speed, 2 resolutions
  // The local design: the 3 x 3 base grid, its star and its moves, 4 points per effect (both
  // continuous at neutral) and as many per move of its design; the step is read.
  json local = request();
  local["grid"] = {{"design", "local"}, {"fr0", 3}, {"fs0", 3}, {"step", 0.15}};
  const DiagnosisCampaign c3 = parse_diagnosis_campaign(local);
  EXPECT_EQ(c3.grid.design, Design::local);
  EXPECT_EQ(c3.grid.step, 0.15);
  EXPECT_EQ(
      planned_jobs(c3),
      (9 + 5 + 4 * kStarMoves + 2 * 4 * (1 + kEffectMoves) + 2 * 5 * 7 + kScreen + 3 * 7 + 2) * 4u +
          kNextTest);
  // Without the next test, its part is not planned.
  json off = request();
  off["next_test"] = false;
  EXPECT_EQ(planned_job_parts(parse_diagnosis_campaign(off)).size(), 3u);
  EXPECT_EQ(planned_jobs(parse_diagnosis_campaign(off)), planned_jobs(c) - kNextTest);
  EXPECT_EQ(c.grid.design, Design::global);
  // Without "effects", every registered effect is a candidate.
  json all = request();
  all.erase("effects");
  EXPECT_EQ(parse_diagnosis_campaign(all).candidates.size(), effect_registry().size());
}

TEST(DiagnosisRequest, BadRequestsNameTheField) {
  const std::vector<std::pair<std::string, std::function<void(json&)>>> cases = {
      {"kind", [](json& r) { r["kind"] = "calibration"; }},
      {"bounds.fr0",
       [](json& r) {
         r["bounds"]["fr0"] = {100, 10};
       }},
      {"bounds.fs0[0]",
       [](json& r) {
         r["bounds"]["fs0"] = {"a", 10};
       }},
      {"bounds.fr1",
       [](json& r) {
         r["bounds"]["fr1"] = {1, 10};
       }},
      {"grid.s", [](json& r) { r["grid"]["s"] = 2; }},
      {"grid.fr0", [](json& r) { r["grid"]["fr0"] = 1.5; }},
      {"grid.design", [](json& r) { r["grid"]["design"] = "adaptive"; }},
      {"grid.step", [](json& r) { r["grid"]["step"] = 0.5; }},
      {"screen", [](json& r) { r["screen"] = "yes"; }},
      {"effects[1]",
       [](json& r) {
         r["effects"] = {"heterogeneity", "gremlins"};
       }},
      {"effects[1]",
       [](json& r) {
         r["effects"] = {"flaws", "flaws"};
       }},
      {"effects", [](json& r) { r["effects"] = "heterogeneity"; }},
      {"job.bond",
       [](json& r) {
         r["job"]["bond"] = {{"fr0", 1}, {"fs0", 1}};
       }},
      {"job.effects", [](json& r) { r["job"]["effects"] = json::object(); }},
      {"job.test", [](json& r) { r["job"]["test"] = "uct"; }},
      {"job.sample.diameter", [](json& r) { r["job"]["sample"]["diameter"] = -1; }},
      {"job", [](json& r) { r.erase("job"); }},
      {"dataset", [](json& r) { r.erase("dataset"); }},
      {"dataset_file", [](json& r) { r["dataset_file"] = "/etc/passwd"; }},
      {"dataset_csv", [](json& r) { r["dataset_csv"] = "id,test\n"; }},
      {"dataset.observations[1].uncertainty",
       [](json& r) { r["dataset"]["observations"][1]["uncertainty"] = -2; }},
      {"dataset.observations",
       [](json& r) {
         for (json& o : r["dataset"]["observations"]) o["role"] = "calibration";
         r["next_test"] = false;
       }},
      {"budget.resolution",
       [](json& r) {
         r["budget"] = {{"resolution", 0.8}};
       }},
      {"budget.resolution[1]",
       [](json& r) {
         r["budget"] = {{"resolution", {1.25, 4}}};
       }},
      {"budget.resolution[1]",
       [](json& r) {
         r["budget"] = {{"resolution", {1.25, 1.25}}};
       }},
      {"budget.resolution",
       [](json& r) {
         r["budget"] = {{"resolution", json::array()}};
       }},
      {"budget.resolution",
       [](json& r) {
         r["budget"] = {{"resolution", "1.25"}};
       }},
      {"budget.speed_factor",
       [](json& r) {
         r["budget"] = {{"speed_factor", 2}};
       }},
      {"budget.points",
       [](json& r) {
         r["budget"] = {{"points", 10}};
       }},
      {"budget.seeds[0]",
       [](json& r) {
         r["budget"] = {{"seeds", {1}}};
       }},
      {"confirm", [](json& r) { r["confirm"] = 0; }},
      {"bootstrap", [](json& r) { r["bootstrap"] = -1; }},
      {"decision.gap_budgets",
       [](json& r) {
         r["decision"] = {{"gap_budgets", 0}};
       }},
      {"decision.min_evidence",
       [](json& r) {
         r["decision"] = {{"min_evidence", -1}};
       }},
      {"decision.g",
       [](json& r) {
         r["decision"] = {{"g", 0.5}};
       }},
      {"decision", [](json& r) { r["decision"] = 2; }},
      {"colour", [](json& r) { r["colour"] = "blue"; }},
  };
  for (const auto& [field, change] : cases) {
    json r = request();
    change(r);
    EXPECT_EQ(refused_field(r), field) << r.dump();
  }
}

// The diagnosis sets platen speeds itself (lab loading rates, the budget's half speed), so a
// template with the engine's "auto" speed is refused, naming the field.
TEST(DiagnosisRequest, AutoPlatenSpeedIsRefused) {
  json r = request();
  r["job"]["loading"]["platen_velocity"] = "auto";
  try {
    parse_diagnosis_campaign(r);
    FAIL() << "accepted";
  } catch (const orch::RequestError& e) {
    EXPECT_EQ(std::string(e.what()),
              "job.loading.platen_velocity: the diagnosis sets platen speeds itself (the lab's "
              "loading rates, the error budget's half speed): give a number, not \"auto\"");
  }
}

// The next test is on unless the request turns it off; anything but true or false is refused.
TEST(DiagnosisRequest, TheNextTestDefaultsOnAndIsRead) {
  EXPECT_TRUE(parse_diagnosis_campaign(request()).next_test);
  json r = request();
  r["next_test"] = false;
  EXPECT_FALSE(parse_diagnosis_campaign(r).next_test);
  r["next_test"] = "no";
  try {
    parse_diagnosis_campaign(r);
    FAIL() << "accepted";
  } catch (const orch::RequestError& e) {
    EXPECT_EQ(e.field, "next_test");
    EXPECT_EQ(std::string(e.what()), "next_test: must be true or false");
  }
}

// A request that may need more jobs than the server's cap is refused naming grid, with what to
// change; without the next test's batch the same request fits a cap that much lower.
TEST(DiagnosisRequest, TheJobCapCountsTheNextTest) {
  const std::size_t planned = planned_jobs(parse_diagnosis_campaign(request()));
  const orch::CampaignKind kind = diagnosis_kind();
  try {
    kind.plan(request(), orch::Limits{planned - 1});
    FAIL() << "accepted";
  } catch (const orch::RequestError& e) {
    EXPECT_EQ(e.field, "grid");
    EXPECT_EQ(std::string(e.what()),
              "grid: the diagnosis may need " + std::to_string(planned) +
                  " jobs, above the server's cap of " + std::to_string(planned - 1) +
                  " per campaign: a smaller grid, grid.design \"local\", fewer effects or "
                  "\"next_test\": false");
  }
  json off = request();
  off["next_test"] = false;
  EXPECT_EQ(kind.plan(off, orch::Limits{planned - 1}).name, "validation");
}

// Screening is on unless the request turns it off; anything but true or false is refused.
TEST(DiagnosisRequest, ScreeningDefaultsOnAndIsRead) {
  EXPECT_TRUE(parse_diagnosis_campaign(request()).screen);
  json r = request();
  r["screen"] = false;
  EXPECT_FALSE(parse_diagnosis_campaign(r).screen);
  r["screen"] = 1;
  try {
    parse_diagnosis_campaign(r);
    FAIL() << "accepted";
  } catch (const orch::RequestError& e) {
    EXPECT_EQ(std::string(e.what()), "screen: must be true or false");
  }
}

TEST(DiagnosisRequest, TheDecisionRuleDefaultsAndIsRead) {
  DiagnosisCampaign c = parse_diagnosis_campaign(request());
  EXPECT_EQ(c.decision.gap_budgets, 1.0);
  EXPECT_EQ(c.decision.min_evidence, 1.0);  // nats: calibrated on null twins (evidence_twin_test)
  json r = request();
  r["decision"] = {{"gap_budgets", 2.4}};
  c = parse_diagnosis_campaign(r);
  EXPECT_EQ(c.decision.gap_budgets, 2.4);
  EXPECT_EQ(c.decision.min_evidence, 1.0);
  r["decision"]["min_evidence"] = 0;
  EXPECT_EQ(parse_diagnosis_campaign(r).decision.min_evidence, 0.0);
  r["decision"]["min_evidence"] = -0.5;
  try {
    parse_diagnosis_campaign(r);
    ADD_FAILURE() << "a negative evidence threshold was accepted";
  } catch (const orch::RequestError& e) {
    EXPECT_EQ(e.field, "decision.min_evidence");
    EXPECT_EQ(std::string(e.what()), "decision.min_evidence: must be 0 or more (nats)");
  }
  // The gap-closure threshold of the earlier rule is no field any more.
  r["decision"] = {{"min_gap_closure", 0.3}};
  try {
    parse_diagnosis_campaign(r);
    ADD_FAILURE() << "decision.min_gap_closure was accepted";
  } catch (const orch::RequestError& e) {
    EXPECT_EQ(std::string(e.what()), "decision.min_gap_closure: unknown field");
  }
}

TEST(DiagnosisRequest, JobsAreCanonicalAndCarryTheEffectAndNumerics) {
  const DiagnosisCampaign c = parse_diagnosis_campaign(request());
  json probe = c.job_template;
  probe["bond"] = {{"fr0", 1}, {"fs0", 1}};
  const JobSpec model = parse_job_template(probe, TestKind::uct);
  const RunPlan plan = plan_runs(c.targets);
  ASSERT_EQ(plan.runs.size(), 4u);
  const RunRequest base{{40, 80, "", 0.0}, {1, 1.0, 1.0}};
  const json tri = job_for(c.job_template, model, plan.runs[2], base);
  EXPECT_EQ(tri["test"], "triaxial");
  EXPECT_EQ(tri["loading"]["confining_pressure"], 50);
  EXPECT_FALSE(tri.contains("effects") && !tri["effects"].empty());
  // s = 0 is the base model's very job, effect named or not: the cache knows it.
  EXPECT_EQ(
      job_for(c.job_template, model, plan.runs[0], {{40, 80, "heterogeneity", 0.0}, {1, 1, 1}}),
      job_for(c.job_template, model, plan.runs[0], base));
  const json het =
      job_for(c.job_template, model, plan.runs[0], {{40, 80, "heterogeneity", 1.0}, {1, 1, 1}});
  EXPECT_DOUBLE_EQ(het["effects"]["heterogeneity"]["weibull_m"].get<double>(),
                   effect_value_at(*find_effect("heterogeneity"), 1.0, model));
  // A finer resolution keeps the continuum: R / r, K_r / r, strengths / r^2.
  const json fine = job_for(c.job_template, model, plan.runs[0], {{40, 80, "", 0}, {1, 1, 2.0}});
  EXPECT_DOUBLE_EQ(fine["sample"]["radius"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(fine["material"]["kr"].get<double>(), 4000);
  EXPECT_DOUBLE_EQ(fine["bond"]["fr0"].get<double>(), 10);
  const json slow = job_for(c.job_template, model, plan.runs[0], {{40, 80, "", 0}, {5, 0.5, 1}});
  EXPECT_DOUBLE_EQ(slow["loading"]["platen_velocity"].get<double>(), 0.025);
  // The template's FCC lattice is seeded: each seed is another cut, kept in the job.
  EXPECT_EQ(slow["sample"]["seed"], 5);
  // An aligned lattice is the same under every seed: every seed gives the template's job (run
  // once); an effect that draws from the seed keeps it.
  json aligned = c.job_template;
  aligned["sample"]["lattice"] = "aligned";
  EXPECT_EQ(job_for(aligned, model, plan.runs[0], {{40, 80, "", 0}, {5, 1, 1}}),
            job_for(aligned, model, plan.runs[0], base));
  const json het5 =
      job_for(c.job_template, model, plan.runs[0], {{40, 80, "heterogeneity", 1.0}, {5, 1, 1}});
  EXPECT_EQ(het5["sample"]["seed"], 5);
}

// Without held-out observations no effect can be judged: effects are accepted for their next test
// (the plan runs the base model's grid and confirmation only, no effect's surfaces), and refused,
// with what to ask instead, when the next test is turned off; with "effects": [] the request is a
// gap location.
TEST(DiagnosisRequest, CalibrationOnlyDatasetTakesEffectsOnlyForTheirNextTest) {
  json r = request();
  for (json& o : r["dataset"]["observations"]) o["role"] = "calibration";
  const DiagnosisCampaign with = parse_diagnosis_campaign(r);
  EXPECT_FALSE(judges_effects(with));
  EXPECT_EQ(with.candidates.size(), 2u);
  std::vector<orch::BudgetPart> parts = planned_job_parts(with);
  ASSERT_EQ(parts.size(), 4u);
  EXPECT_EQ(parts[0].budget, 9 * 4);                // the base grid alone
  EXPECT_EQ(parts[2].budget, 1 * (1 + 2 + 4) * 4);  // the base model confirmed alone
  EXPECT_EQ(parts[3].name, "next_test");
  r["next_test"] = false;
  try {
    parse_diagnosis_campaign(r);
    FAIL() << "accepted";
  } catch (const orch::RequestError& e) {
    EXPECT_EQ(e.field, "dataset.observations");
    EXPECT_EQ(std::string(e.what()),
              "dataset.observations: has no held_out observation, so no effect can be judged (a "
              "better calibration fit proves nothing) and with \"next_test\": false none gets the "
              "test that would show it; ask for \"next_test\": true, or \"effects\": [] to only "
              "locate the gap");
  }
  r["effects"] = json::array();
  const DiagnosisCampaign c = parse_diagnosis_campaign(r);
  EXPECT_TRUE(c.candidates.empty());
  EXPECT_EQ(count_role(c.targets, Role::held_out), 0u);
  // Nothing to tell apart: no next test's batch is planned.
  parts = planned_job_parts(c);
  ASSERT_EQ(parts.size(), 3u);
  EXPECT_EQ(parts.back().name, "confirm");
}

// The example request, with its dataset_file inlined the way `rockcal diagnose` does.
TEST(DiagnosisRequest, ExampleRequestParses) {
  const std::string dir = std::string(ROCKCAL_SOURCE_DIR) + "/examples/";
  json r = json::parse(std::ifstream(dir + "diagnose_twin.json"));
  r["dataset"] = json::parse(std::ifstream(dir + r["dataset_file"].get<std::string>()));
  r.erase("dataset_file");
  const DiagnosisCampaign c = parse_diagnosis_campaign(r);
  EXPECT_EQ(c.targets.size(), 8u);
  EXPECT_EQ(count_role(c.targets, Role::held_out), 4u);
  EXPECT_EQ(plan_runs(c.targets).runs.size(), 7u);  // the UCT's peak and modulus share a run
  EXPECT_EQ(c.candidates.size(), effect_registry().size());
  // packing jumps at neutral: it runs its own s slice instead of sharing the base grid's.
  EXPECT_EQ(c.candidates[1].effect, "packing");
  EXPECT_GT(c.candidates[1].s_floor, 0.0);
  EXPECT_FALSE(c.candidates[1].shares_base_grid());
  const ModelPoint lowest = model_point(c, c.candidates[1], std::vector<double>{0.5, 0.5, 0.0});
  EXPECT_TRUE(effect_on(lowest));  // u = 0 is a random packing, not the base model's FCC
  EXPECT_DOUBLE_EQ(lowest.s, kDiscontinuousFloor);
  // interaction_range jumps at neutral too, but in this FCC template nothing is bonded beyond
  // touching below sqrt(2): its walk starts there, so no level of its design is the base model.
  const auto range = std::find_if(c.candidates.begin(), c.candidates.end(), [](const Candidate& k) {
    return k.effect == "interaction_range";
  });
  ASSERT_NE(range, c.candidates.end());
  EXPECT_GT(range->value_at(range->s_at(0.0)), std::sqrt(2.0));
  EXPECT_NEAR(range->value_at(range->s_at(0.0)), std::sqrt(2.0) * 1.01, 1e-9);
  EXPECT_DOUBLE_EQ(range->value_at(range->s_at(1.0)), 1.5);
  // A 5 x 5 (x 5) grid: 25 + 7 x 25 x 4 (+ packing's, interaction_range's and brazilian_flats'
  // own 25 x 5), twice 5 points x 10 budget runs (reference, 4 seeds, half speed, 4
  // resolutions), the screen's 3 points for each of 10 effects at two points and the base's at the
  // second, every confirmed: 8 x (3 + 4) and the base model at each of the 7 confirmed effects'
  // strengths; the next test's base at its fit and two steps (and at the balanced point), the 10
  // effects and the base under the 9 budget variants on the 7 runs and the menu's 8 more (its
  // fast UCT is the dataset's).
  EXPECT_EQ(c.grid.fr0, 5);
  EXPECT_EQ(c.grid.s, 5);
  EXPECT_EQ(c.budget.resolutions, (std::vector<double>{1.125, 1.25, 1.375, 1.5}));
  EXPECT_EQ(planned_jobs(c),
            (25 + 7 * 100 + 3 * 125 + 2 * 5 * 10 + 1 + 2 * 3 * 10 + 8 * 7 + 7) * 7u +
                (2 * 3 + 10 + 9) * (7 + 8));
}

TEST(DiagnosisRuns, ARunWithoutAPeakHasNoValueAtAll) {
  const json peaked = {{"test", "uct"},
                       {"peak_load", 900.0},
                       {"youngs_modulus", 50.0},
                       {"peak_reached", true},
                       {"stop_reason", "post_peak"}};
  EXPECT_EQ(observable_value(peaked, Observable::peak_load), 900.0);
  EXPECT_EQ(observable_value(peaked, Observable::youngs_modulus), 50.0);
  // The largest load within loading.max_strain (or the step limit, or a cancel) is no peak, and
  // the run is a failed run: not even its modulus counts.
  for (const char* why : {"max_strain", "max_steps", "cancelled"}) {
    json stopped = peaked;
    stopped["peak_reached"] = false;
    stopped["stop_reason"] = why;
    EXPECT_FALSE(observable_value(stopped, Observable::peak_load).has_value()) << why;
    EXPECT_FALSE(observable_value(stopped, Observable::youngs_modulus).has_value()) << why;
  }
}

TEST(DiagnosisBudget, IsTheRmsChangeOverItsPointsAndTheLargestOverTheVariants) {
  // Two points, two variants, three targets. Target 0: the resolution moves it by e^0.3 at one
  // point and e^-0.1 at the other: rms 0.2236, above the speed variant's 0.05. Target 1 failed at
  // point 1's reference, so point 0 alone counts. Target 2 never ran: the largest budget.
  const auto run = [](std::vector<std::optional<double>> v) { return RunOutcome{v, ""}; };
  const std::vector<RunOutcome> refs{run({100.0, 50.0, std::nullopt}),
                                     run({200.0, std::nullopt, std::nullopt})};
  const std::vector<std::vector<RunOutcome>> changed{
      {run({100.0 * std::exp(0.05), 50.0 * std::exp(0.02), std::nullopt}),
       run({100.0 * std::exp(0.3), 50.0 * std::exp(-0.4), std::nullopt})},
      {run({200.0 * std::exp(-0.05), 80.0, std::nullopt}),
       run({200.0 * std::exp(-0.1), 90.0, std::nullopt})}};
  const Budget b = numerical_budget(
      {{"speed x0.5", {1, 0.5, 1}, "speed"}, {"resolution x1.25", {1, 1, 1.25}, "resolution"}},
      refs, changed);
  EXPECT_EQ(b.points, 2);
  EXPECT_NEAR(b.change[0][0], 0.05, 1e-12);
  EXPECT_NEAR(b.change[1][0], std::sqrt((0.09 + 0.01) / 2), 1e-12);
  EXPECT_NEAR(b.per_target[0], std::sqrt(0.05), 1e-12);
  EXPECT_NEAR(b.per_target[1], 0.4, 1e-12);
  EXPECT_TRUE(std::isnan(b.change[0][2]));
  EXPECT_FALSE(b.measured[2]);
  EXPECT_NEAR(b.per_target[2], 0.4, 1e-12);
  // The points: the fit first, then its neighbours along each strength.
  const auto offsets = budget_offsets(5);
  ASSERT_EQ(offsets.size(), 5u);
  EXPECT_EQ(offsets[0], (std::vector<double>{0, 0}));
  EXPECT_EQ(offsets[1], (std::vector<double>{kBudgetStep, 0}));
  EXPECT_EQ(budget_offsets(1).size(), 1u);
  // On the edge of the box the step outwards clamps onto the fit itself: that point runs once.
  const auto edge = budget_points({1.0, 0.5}, 5);
  ASSERT_EQ(edge.size(), 4u);
  EXPECT_EQ(edge[0], (std::vector<double>{1.0, 0.5}));
  EXPECT_EQ(edge[1], (std::vector<double>{1.0 - kBudgetStep, 0.5}));
  EXPECT_EQ(budget_points({0.5, 0.5}, 5).size(), 5u);
  EXPECT_EQ(budget_offsets(9).size(), 9u);

  // Variants of one kind are draws of one source and pool by rms; kinds count by the largest.
  // Target 0 at one point: two resolutions move it by 0.3 and 0.1 (rms 0.2236), the speed by
  // 0.25: the speed's 0.25 is the budget. Target 1: resolutions 0.4 and 0.2 (rms 0.3162) beat
  // the speed's 0.1.
  const std::vector<RunOutcome> ref1{run({100.0, 50.0})};
  const std::vector<std::vector<RunOutcome>> by_kind{
      {run({100.0 * std::exp(0.25), 50.0 * std::exp(0.1)}),
       run({100.0 * std::exp(0.3), 50.0 * std::exp(-0.4)}),
       run({100.0 * std::exp(-0.1), 50.0 * std::exp(0.2)})}};
  BudgetSpec spec;
  spec.seeds = {};
  spec.resolutions = {1.25, 1.5};
  const std::vector<BudgetVariant> variants = budget_variants(spec, 1);
  ASSERT_EQ(variants.size(), 3u);
  EXPECT_EQ(variants[1].name, "resolution x1.25");
  EXPECT_EQ(variants[2].name, "resolution x1.5");
  EXPECT_EQ(variants[2].kind, "resolution");
  EXPECT_EQ(variants[2].numerics.resolution, 1.5);
  const Budget pooled = numerical_budget(variants, ref1, by_kind);
  EXPECT_NEAR(pooled.per_target[0], 0.25, 1e-12);
  EXPECT_NEAR(pooled.per_target[1], std::sqrt((0.16 + 0.04) / 2), 1e-12);
}

// The budget measures only the errors that lie between the data and the model: a same-resolution
// twin shares the model's lattice cut and platen speed, so charging it their spread (0.38-0.89 in
// ln on the demo twins) would hide every gap smaller than that; lab data carry all three.
TEST(DiagnosisBudget, ChargesOnlyTheErrorsTheDataCarry) {
  BudgetSpec spec;
  spec.seeds = {2, 3};
  spec.resolutions = {1.25, 1.5};
  auto kinds = [&](Origin origin) {
    std::vector<std::string> out;
    for (const BudgetVariant& v : budget_variants(spec, 1, origin)) out.push_back(v.kind);
    return out;
  };
  using V = std::vector<std::string>;
  EXPECT_EQ(kinds(Origin::lab), (V{"seed", "seed", "speed", "resolution", "resolution"}));
  EXPECT_EQ(kinds(Origin::finer_model), (V{"seed", "seed", "resolution", "resolution"}));
  EXPECT_EQ(kinds(Origin::same_resolution_model), (V{"seed", "seed"}));
  EXPECT_EQ(budget_runs_per_point(spec, Origin::same_resolution_model), 3u);
  EXPECT_EQ(budget_runs_per_point(spec, Origin::lab), 6u);
  for (const Origin origin : {Origin::lab, Origin::same_resolution_model, Origin::finer_model}) {
    const std::vector<ErrorTerm> terms = error_terms(origin);
    ASSERT_EQ(terms.size(), 3u);
    for (const ErrorTerm& t : terms) EXPECT_FALSE(t.why.empty()) << t.kind;
  }
}

// A refinement that moves every observation the way a change of the strengths would is absorbed
// when the model is calibrated: it is a shared bias, not an error of a calibrated prediction.
// What the re-fit cannot follow (a move of a held-out observation alone) is charged in full; the
// seed and speed variants are never re-fitted.
TEST(DiagnosisBudget, AResolutionShiftTheStrengthsAbsorbIsNoError) {
  // Targets 0, 1 calibration, 2 held out. d ln / dz: target 0 on F_r0, 1 on F_s0, 2 on both.
  const std::vector<std::array<double, 2>> jacobian{{1.0, 0.0}, {0.0, 1.0}, {0.5, 0.5}};
  const std::vector<double> weight{2500, 2500, 0};
  // 0.2 everywhere is dz = (0.2, 0.2): nothing left.
  for (double left : change_after_refit({0.2, 0.2, 0.2}, jacobian, weight)) {
    EXPECT_NEAR(left, 0.0, 1e-12);
  }
  // A held-out move the calibration targets do not see stays whole.
  const auto held_out_only = change_after_refit({0.0, 0.0, 0.3}, jacobian, weight);
  EXPECT_NEAR(held_out_only[0], 0.0, 1e-12);
  EXPECT_NEAR(held_out_only[2], 0.3, 1e-12);
  // Calibration moves (0.1, 0.3) re-fit exactly; the held-out target keeps what its own response
  // does not explain: 0.5 - (0.5 x 0.1 + 0.5 x 0.3) = 0.3.
  EXPECT_NEAR(change_after_refit({0.1, 0.3, 0.5}, jacobian, weight)[2], 0.3, 1e-12);
  // One calibration direction (both calibration targets respond to F_r0 alone): the re-fit moves
  // F_r0 only, and a missing change stays missing.
  const std::vector<std::array<double, 2>> one_direction{{1.0, 0.0}, {2.0, 0.0}, {1.0, 1.0}};
  const auto rank_one = change_after_refit({0.1, 0.2, std::numeric_limits<double>::quiet_NaN()},
                                           one_direction, weight);
  EXPECT_NEAR(rank_one[0], 0.0, 1e-12);
  EXPECT_NEAR(rank_one[1], 0.0, 1e-12);
  EXPECT_TRUE(std::isnan(rank_one[2]));

  // In the budget: one point; the seed and the resolution both move every target by e^0.2.
  const auto run = [](std::vector<std::optional<double>> v) { return RunOutcome{v, ""}; };
  const std::vector<RunOutcome> refs{run({100.0, 50.0, 70.0})};
  const double e = std::exp(0.2);
  const std::vector<std::vector<RunOutcome>> changed{
      {run({100.0 * e, 50.0 * e, 70.0 * e}), run({100.0 * e, 50.0 * e, 70.0 * e})}};
  const StrengthResponse response{{jacobian}, weight};
  const Budget b = numerical_budget(
      {{"seed 2", {2, 1, 1}, "seed"}, {"resolution x1.25", {1, 1, 1.25}, "resolution"}}, refs,
      changed, &response);
  EXPECT_EQ(b.refitted, (std::vector<bool>{false, true}));
  EXPECT_NEAR(b.change[0][2], 0.2, 1e-12);
  EXPECT_NEAR(b.change[1][2], 0.0, 1e-12);
  EXPECT_NEAR(b.per_target[2], 0.2, 1e-12);  // the seed's, not the absorbed resolution's
}

TEST(DiagnosisRefinement, AWorseRunHalvesTheNextStepTowardsTheSameFit) {
  TrustRegion t{0.25};
  EXPECT_TRUE(t.record({0.5, 0.5}, 4.0, {1.0}));
  // A re-fit 0.4 away: the first step is cut to the radius, along the same direction.
  auto z = t.next({0.9, 0.3}, 0.01);
  ASSERT_TRUE(z.has_value());
  EXPECT_NEAR((*z)[0], 0.75, 1e-12);
  EXPECT_NEAR((*z)[1], 0.375, 1e-12);
  // That run is worse: the best stays, and the same re-fit now gets half the step (0.125).
  EXPECT_FALSE(t.record(*z, 6.0, {2.0}));
  EXPECT_EQ(t.best_z, (std::vector<double>{0.5, 0.5}));
  EXPECT_EQ(t.best_ln, (std::vector<double>{1.0}));
  z = t.next({0.9, 0.3}, 0.01);
  ASSERT_TRUE(z.has_value());
  EXPECT_NEAR((*z)[0], 0.625, 1e-12);
  EXPECT_NEAR((*z)[1], 0.4375, 1e-12);
  // A better run is the new best; a re-fit within the radius is taken whole.
  EXPECT_TRUE(t.record(*z, 3.0, {3.0}));
  z = t.next({0.7, 0.45}, 0.01);
  ASSERT_TRUE(z.has_value());
  EXPECT_NEAR((*z)[0], 0.7, 1e-12);
  // Worse again after that 0.075 step: the radius is 0.0375.
  EXPECT_FALSE(t.record(*z, 5.0, {}));
  EXPECT_NEAR(t.radius, 0.0375, 1e-12);
  // A re-fit that no longer moves has settled.
  EXPECT_FALSE(t.next({0.625 + 0.005, 0.4375}, 0.01).has_value());
  // Worse runs keep halving: 0.0375 -> 0.01875 -> 0.009375, below the settling step: done.
  for (double expected : {0.01875, 0.009375}) {
    z = t.next({0.7, 0.45}, 0.01);
    ASSERT_TRUE(z.has_value());
    EXPECT_FALSE(t.record(*z, 5.0, {}));
    EXPECT_NEAR(t.radius, expected, 1e-12);
  }
  EXPECT_FALSE(t.next({0.7, 0.45}, 0.01).has_value());
}

}  // namespace
}  // namespace rockcal::diagnosis
