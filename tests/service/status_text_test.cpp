// What `rockcal status` shows a reader: a calibration's progress line (evaluations of the budget,
// best misfit and point, running jobs, an ETA from the measured pace, never "ETA 0s" while
// running), a diagnosis's (jobs of its planned phases), the summary table that replaces the
// report's JSON at the end, the sweep's summary, and the pacing of progress lines in a log.
#include <gtest/gtest.h>

#include "api/cli/calibration_text.hpp"
#include "api/cli/status_text.hpp"

namespace rockcal::api {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

// A running calibration as GET /api/v1/campaigns/{id} returns it (calibration_kind.cpp's live
// summary and its progress model): 3 evaluations of 40 done, the second the best, 2 seed re-runs
// still to come, the ETA as the model gives it.
json running_calibration(json eta_seconds) {
  return json::parse(R"({
    "id": 7, "kind": "calibration", "name": "lab", "state": "running",
    "progress": {"total": 8, "queued": 0, "running": 2, "succeeded": 6, "failed": 0,
                 "cancelled": 0, "cached": 0, "fraction": 0.75, "eta_seconds": 0},
    "summary": {"kind": "calibration", "stop_reason": null, "evaluations": 3,
                "max_evaluations": 40, "scatter_runs": 2, "realisations": 1,
                "history": [
                  {"index": 0, "ok": true, "fr0": 10, "fs0": 20, "misfit": 0.5},
                  {"index": 1, "ok": true, "fr0": 41.25, "fs0": 88.5, "misfit": 0.01234},
                  {"index": 2, "ok": false, "fr0": 900, "fs0": 900, "misfit": 0.001}],
                "progress": {"unit": "evaluations", "done": 3, "budget": 40,
                             "parts": [{"name": "search", "budget": 40}], "seed_reruns": 2,
                             "left": 39, "fraction": 0.075, "eta_seconds": null}}})")
      .patch(json::array({{{"op", "replace"},
                           {"path", "/summary/progress/eta_seconds"},
                           {"value", eta_seconds}}}));
}

TEST(CalibrationProgress, EvaluationsOfTheBudgetBestMisfitRunningJobsAndEta) {
  // The failed evaluation's penalty is no best.
  EXPECT_EQ(progress_line(running_calibration(390.0)),
            "campaign 7 running: 3 of 40 evaluations done (+2 seed re-runs), best misfit 0.0123 "
            "at F_r0 = 41.25, F_s0 = 88.5, 2 jobs running, ETA 6m30s (full budget)");
}

TEST(CalibrationProgress, EtaUnknownUntilAnEvaluationHasRun) {
  json c = running_calibration(nullptr);
  c["summary"]["progress"]["done"] = 0;
  c["summary"]["history"] = json::array();
  EXPECT_EQ(progress_line(c),
            "campaign 7 running: 0 of 40 evaluations done (+2 seed re-runs), 2 jobs running, "
            "ETA unknown");
}

TEST(CalibrationProgress, OneJobIsOneJob) {
  json c = running_calibration(nullptr);
  c["progress"]["running"] = 1;
  EXPECT_NE(progress_line(c).find(", 1 job running, "), std::string::npos) << progress_line(c);
}

TEST(CalibrationProgress, NothingLeftIsFinishing) {
  // Budget spent and no re-runs left: the driver is writing its report.
  json c = running_calibration(nullptr);
  c["summary"]["progress"]["done"] = 40;
  c["summary"]["progress"]["left"] = 0;
  const std::string line = progress_line(c);
  EXPECT_EQ(line.substr(line.rfind(", ")), ", finishing");
}

// The budget's parts are named when it has more than the search's.
TEST(CalibrationProgress, TheValleyTraceIsNamedInTheBudget) {
  json c = running_calibration(390.0);
  c["summary"]["progress"]["budget"] = 64;
  c["summary"]["progress"]["parts"].push_back({{"name", "valley trace"}, {"budget", 24}});
  EXPECT_EQ(progress_line(c).rfind("campaign 7 running: 3 of 64 evaluations done (search 40, "
                                   "valley trace 24; +2 seed re-runs), best misfit",
                                   0),
            0u)
      << progress_line(c);
}

TEST(CalibrationProgress, OtherKindsKeepTheJobsLine) {
  json c = running_calibration(390.0);
  c["kind"] = "sweep";
  c.erase("summary");
  c["progress"]["eta_seconds"] = 30;
  EXPECT_EQ(progress_line(c),
            "campaign 7 running [#######################.......] 75% 6/8 done, 2 running, 0 "
            "queued, ETA 30s");
}

// A finished calibration's report (report_json.cpp) with lab units, ensembles of 3 and the
// consistent set, unique flag and suggestion.
json lab_report() {
  return json::parse(R"({
    "kind": "calibration", "name": "lab", "stop_reason": "tolerance_met",
    "verdict": "feasible", "verdict_reason": "both peak loads within 2% of their targets",
    "evaluations": 23, "failed_evaluations": 1, "max_evaluations": 40, "realisations": 3,
    "best": {"fr0": 41.25, "fs0": 88.5, "misfit": 0.000125, "evaluation": 17,
             "uct": {"peak_load": 2020, "target": 2000, "relative_error": 0.01, "se": 8, "n": 3},
             "btt": {"peak_load": 297, "target": 300, "relative_error": -0.01, "se": 1.5, "n": 3},
             "lab": {"fr0": 4125, "fs0": 8850,
                     "uct": {"peak_load": 202000, "target": 200000, "relative_error": 0.01},
                     "btt": {"peak_load": 29700, "target": 30000, "relative_error": -0.01}}},
    "scatter": {"runs": [], "uct": null, "btt": null},
    "consistent": {"fr0": [39, 44], "fs0": [80, 95], "ratio": [1.9, 2.3],
                   "points": [{"fr0": 40}, {"fr0": 42}, {"fr0": 43}]},
    "unique": false,
    "suggestion": {"observable": "triaxial peak at 5 MPa", "values": [5e6, 10e6],
                   "why": "separates F_s0 from F_r0 along the valley"},
    "pace": {"wall_seconds": 754, "evaluations_timed": 23, "seconds_per_evaluation": 32.8},
    "progress": {"unit": "evaluations", "done": 23, "budget": 40,
                 "parts": [{"name": "search", "budget": 40}], "seed_reruns": 0, "left": 0,
                 "fraction": 1, "eta_seconds": 0}})");
}

TEST(CalibrationSummary, VerdictStrengthsLoadsAgainstTargetsConsistentSetAndBudget) {
  json c = {{"id", 7},
            {"kind", "calibration"},
            {"name", "lab"},
            {"state", "succeeded"},
            {"summary", lab_report()}};
  EXPECT_EQ(summary_text(c),
            "calibration 7 \"lab\" succeeded\n"
            "verdict: feasible - both peak loads within 2% of their targets\n"
            "best bond strengths  model units   lab units (N)\n"
            "  F_r0                     41.25            4125\n"
            "  F_s0                      88.5            8850\n"
            "load   target (N)   simulated (N)       error\n"
            "  UCT      200000   202000 ± 800        +1.00% ± 0.40%  (mean of 3)\n"
            "  BTT       30000   29700 ± 150         -1.00% ± 0.50%  (mean of 3)\n"
            "  best misfit 0.000125 at evaluation 17\n"
            "consistent with the targets: F_r0 [39, 44], F_s0 [80, 95], ratio [1.9, 2.3] (3 "
            "points)\n"
            "unique: no\n"
            "suggestion: measure triaxial peak at 5 MPa (5e+06, 1e+07): separates F_s0 from F_r0 "
            "along the valley\n"
            "evaluations: 23 of 40, 1 failed, 3 packings each, stopped: tolerance_met, wall time "
            "12m34s\n");
}

TEST(CalibrationSummary, ModelUnitsSingleRunsAndNoConsistentSetAreShownWithoutThem) {
  json s = lab_report();
  s["best"].erase("lab");
  for (const char* t : {"uct", "btt"}) {
    s["best"][t]["se"] = nullptr;
    s["best"][t]["n"] = 1;
  }
  s["scatter"]["uct"] = {{"mean", 2000}, {"stddev", 50}, {"cv", 0.025}, {"runs", 3}};
  s["scatter"]["btt"] = {{"mean", 300}, {"stddev", 3}, {"cv", 0.01}, {"runs", 3}};
  for (const char* k : {"consistent", "unique", "suggestion", "pace"}) s.erase(k);
  s["failed_evaluations"] = 0;
  s["realisations"] = 1;
  EXPECT_EQ(calibration_text(s),
            "verdict: feasible - both peak loads within 2% of their targets\n"
            "best bond strengths  model units\n"
            "  F_r0                     41.25\n"
            "  F_s0                      88.5\n"
            "load       target   simulated           error\n"
            "  UCT        2000   2020                +1.00%\n"
            "  BTT         300   297                 -1.00%\n"
            "  seed scatter of the best point: UCT cv 2.50% over 3 packings, BTT cv 1.00% over 3 "
            "packings\n"
            "  best misfit 0.000125 at evaluation 17\n"
            "evaluations: 23 of 40, stopped: tolerance_met\n");
}

// A multi-fidelity campaign's answer is its last fine step: the table lists them after the coarse
// search's best point.
TEST(CalibrationSummary, FineStepsFollowTheCoarseSearch) {
  json s = lab_report();
  for (const char* k : {"consistent", "unique", "suggestion", "pace"}) s.erase(k);
  s["fidelity"] = {
      {"met", false},
      {"steps",
       {{{"fr0", 32.86},
         {"fs0", 50.58},
         {"uct", {{"relative_error", 0.1362}}},
         {"btt", {{"relative_error", 0.0798}}},
         {"error", ""}},
        {{"fr0", 31.5}, {"fs0", 44.69}, {"error", "a fine run ended without a peak load"}}}}};
  const std::string text = calibration_text(s);
  EXPECT_NE(text.find("fine specimen (2 corrections, not met; the strengths above are the coarse "
                      "search's):\n"
                      "  F_r0 = 32.86, F_s0 = 50.58: UCT +13.62%, BTT +7.98%\n"
                      "  F_r0 = 31.5, F_s0 = 44.69: a fine run ended without a peak load\n"
                      "evaluations: "),
            std::string::npos)
      << text;
}

TEST(CalibrationSummary, NoSuccessfulEvaluationSaysSoWithoutATable) {
  json s = {{"verdict", "failed"},       {"verdict_reason", "no evaluation succeeded"},
            {"best", nullptr},           {"evaluations", 4},
            {"failed_evaluations", 4},   {"max_evaluations", 40},
            {"stop_reason", "converged"}};
  s["progress"] = lab_report()["progress"];
  s["progress"]["done"] = 4;
  EXPECT_EQ(calibration_text(s),
            "verdict: failed - no evaluation succeeded\n"
            "evaluations: 4 of 40, 4 failed, stopped: converged\n");
}

// The closing line counts against the budget the progress line counted down, from the same model
// (the quick start once ended on "42 of 40" after a bar that had said "of 64").
TEST(CalibrationSummary, TheBudgetIncludesTheValleyTrace) {
  json s = {{"verdict", "failed"},
            {"verdict_reason", "no evaluation succeeded"},
            {"best", nullptr},
            {"evaluations", 42},
            {"failed_evaluations", 3},
            {"max_evaluations", 40},
            {"consistency_evaluations", 24},
            {"stop_reason", "tolerance_met"}};
  s["progress"] = lab_report()["progress"];
  s["progress"]["done"] = 42;
  s["progress"]["budget"] = 64;
  s["progress"]["parts"].push_back({{"name", "valley trace"}, {"budget", 24}});
  EXPECT_EQ(calibration_text(s),
            "verdict: failed - no evaluation succeeded\n"
            "evaluations: 42 of 64 (search 40, valley trace 24), 3 failed, stopped: "
            "tolerance_met\n");
}

// A diagnosis's line (rockcal status, rockcal diagnose and rockcal twin share it): its progress
// model (jobs done of the ones it plans, each phase named, the ETA of what is left) and its phase.
// A bayes calibration's summary with its posterior, for the summaries below.
json posterior_load(double target, double mean, double err) {
  return json{{"target", target},
              {"mean", mean},
              {"interval", {mean * 0.9, mean * 1.1}},
              {"relative_error", err},
              {"run_sd", 0.2}};
}

json bayes_summary() {
  return {{"kind", "calibration"},
          {"verdict", "feasible"},
          {"verdict_reason", "met"},
          {"posterior",
           {{"runs", 40},
            {"points", 30},
            {"level", 0.9},
            {"lab_uncertainty", {{"uct", 0.1}, {"btt", 0.1}, {"source", "request"}}},
            {"estimate", {{"fr0", 60.0}, {"fs0", 120.0}}},
            {"fr0", {50.0, 70.0}},
            {"fs0", {100.0, 140.0}},
            {"uct", posterior_load(1000, 1001, 0.001)},
            {"btt", posterior_load(100, 99.5, -0.005)},
            {"unique", true},
            {"why", "narrow"}}}};
}

// A bayes calibration's summary: the posterior's intervals and each load against its target, a
// further target's row named beside the UCT and BTT.
TEST(CalibrationSummary, APosteriorShowsItsIntervalsAndFurtherTargets) {
  json further = posterior_load(5000, 5100, 0.02);
  further["name"] = "triaxial at 10 Pa";
  json summary = bayes_summary();
  summary["posterior"]["further"] = {further};
  summary["rock_properties"] = {
      {"units", "lab"},
      {"ucs_pa", {{"value", 105.2e6}, {"interval", {98.1e6, 112.0e6}}}},
      {"bts_pa", {{"value", 17.5e6}, {"interval", {16.8e6, 18.2e6}}}},
      {"youngs_modulus_pa", {{"value", 11.2e9}, {"runs", 2}, {"lab", 12.33e9}}},
      {"poisson_ratio", {{"value", nullptr}, {"runs", 0}, {"lab", 0.2}}}};
  const std::string text = calibration_text(summary);
  EXPECT_NE(text.find("  F_r0              60  [50, 70]"), std::string::npos) << text;
  EXPECT_NE(text.find("  more          5000          5100  [4590, 5610]              +2.00%  "
                      "(triaxial at 10 Pa)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("unique: yes - narrow"), std::string::npos) << text;
  EXPECT_NE(text.find("rock at the estimate (lab units): UCS 105.2 MPa [98.1, 112], BTS 17.5 MPa "
                      "[16.8, 18.2]; E 11.2 GPa (lab 12.3) and nu not measured from 2 check runs"),
            std::string::npos)
      << text;
}

// Without the stiffness stage E and nu are the check runs' UCT means; nu measured on fewer of
// them (a run answered from a store made before the UCT measured nu) says on how many.
TEST(CalibrationSummary, TheRocksNuFromTheCheckRunsSaysHowManyMeasuredIt) {
  json summary = bayes_summary();
  auto rock = [](int nu_runs) {
    return json{
        {"units", "lab"},
        {"ucs_pa", {{"value", 133.5e6}, {"interval", {129.3e6, 137.9e6}}}},
        {"bts_pa", {{"value", 22.28e6}, {"interval", {21.7e6, 22.87e6}}}},
        {"youngs_modulus_pa",
         {{"value", 1.3e9}, {"runs", 2}, {"measure", "uct"}, {"lab", 12.33e9}}},
        {"poisson_ratio", {{"value", 0.6}, {"runs", nu_runs}, {"measure", "uct"}, {"lab", 0.2}}}};
  };
  summary["rock_properties"] = rock(2);
  std::string text = calibration_text(summary);
  EXPECT_NE(text.find("; E 1.3 GPa (lab 12.3) and nu 0.6 (lab 0.2) from 2 check runs\n"),
            std::string::npos)
      << text;
  summary["rock_properties"] = rock(1);
  text = calibration_text(summary);
  EXPECT_NE(text.find("; E 1.3 GPa (lab 12.3) and nu 0.6 (lab 0.2) from 2 check runs (nu from 1)"),
            std::string::npos)
      << text;
  // The estimate moved after the check runs: E and nu are theirs, at their own point, and the
  // check line says where they ran.
  summary["rock_properties"] = rock(2);
  summary["posterior"]["checked_at"] = {{"fr0", 59.58}, {"fs0", 39.47}};
  summary["posterior"]["estimate_moved_after_check"] = true;
  summary["posterior"]["uct"]["check"] = {{"relative_error", -0.1448},
                                          {"relative_to_prediction", -0.1718},
                                          {"sd", 0.094},
                                          {"runs", 2},
                                          {"agrees", true}};
  text = calibration_text(summary);
  EXPECT_NE(text.find("; E 1.3 GPa (lab 12.3) and nu 0.6 (lab 0.2) from 2 check runs at (F_r0 "
                      "59.58, F_s0 39.47)\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("  check runs at (F_r0 59.58, F_s0 39.47), the estimate before them (the "
                      "estimate moved with them; no run there): UCT -14.48% of the target"),
            std::string::npos)
      << text;
}

// Check runs that gave no loads: the summary says where they ran and why, not "check runs at the
// estimate" with nothing after it.
TEST(CalibrationSummary, ChecksWithoutLoadsSayWhereTheyRanAndWhy) {
  json summary = bayes_summary();
  summary["posterior"]["checked_at"] = {{"fr0", 34.62}, {"fs0", 52.93}};
  summary["posterior"]["check_failed"] = "uct: no peak: the load was still rising";
  const std::string text = calibration_text(summary);
  EXPECT_NE(text.find("  check runs at (F_r0 34.62, F_s0 52.93): no loads (uct: no peak: the load "
                      "was still rising)\n"),
            std::string::npos)
      << text;
  summary["posterior"]["check_failed"] = nullptr;
  EXPECT_EQ(calibration_text(summary).find("no loads"), std::string::npos);
}

// E and nu as targets: the stiffness stage's line in lab units (E and its target in GPa, nu and
// its target, the stiffnesses and the stage's reason), and the rock's E and nu from the elastic
// test with the UCT's slope beside it.
TEST(CalibrationSummary, TheStiffnessStageShowsEAndNuInLabUnits) {
  json summary = bayes_summary();
  summary["stiffness"] = {
      {"kr", 17822.7},
      {"ks_over_kr", 0.0966},
      {"youngs_modulus_pa", {{"target", 4000.0}, {"measured", 3999.9}}},
      {"poisson_ratio", {{"target", 0.3}, {"measured", 0.3001}}},
      {"lab", {{"youngs_modulus_pa", {{"target", 69e9}, {"measured", 68.9e9}}}}},
      {"why", "nu 0.300 meets the target 0.300 at K_s/K_r 0.0966."}};
  summary["rock_properties"] = {
      {"units", "lab"},
      {"ucs_pa", {{"value", 200e6}, {"interval", {190e6, 210e6}}}},
      {"bts_pa", {{"value", 8.8e6}, {"interval", {8.5e6, 9.1e6}}}},
      {"youngs_modulus_pa",
       {{"value", 68.9e9}, {"runs", 4}, {"measure", "elastic"}, {"uct", 31.2e9}, {"lab", 69e9}}},
      {"poisson_ratio",
       {{"value", 0.3001}, {"runs", 1}, {"measure", "elastic"}, {"uct", nullptr}, {"lab", 0.3}}}};
  const std::string text = calibration_text(summary);
  EXPECT_NE(text.find("stiffness (lab units, elastic test): E 68.9 GPa (target 69 GPa) and nu 0.3 "
                      "(target 0.3) at K_r 1.782e+04, K_s/K_r 0.0966 - nu 0.300 meets the target "
                      "0.300 at K_s/K_r 0.0966.\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("rock at the estimate (lab units): UCS 200 MPa [190, 210], BTS 8.8 MPa "
                      "[8.5, 9.1]; E 68.9 GPa (lab 69) and nu 0.3 (lab 0.3) from the elastic test "
                      "(mean of 4 packings) (UCT slope 31.2 GPa)\n"),
            std::string::npos)
      << text;
}

TEST(DiagnosisProgress, JobsOfThePlannedPhasesEtaAndThePhase) {
  json c = running_calibration(390.0);
  c["kind"] = "diagnosis";
  c["summary"] = json::parse(R"({"phase": "budget", "step": 2, "steps": 4, "runs": 12,
    "progress": {"unit": "jobs", "done": 30, "budget": 134, "left": 104, "fraction": 0.2239,
                 "parts": [{"name": "grid", "budget": 54}, {"name": "budget", "budget": 40},
                           {"name": "confirm", "budget": 40}], "eta_seconds": 208}})");
  EXPECT_EQ(progress_line(c),
            "campaign 7 running: 30 of 134 jobs done (grid 54, budget 40, confirm 40), 2 jobs "
            "running, ETA 3m28s (full budget)  [2/4 budget]");
  // Before the driver states a model (or a kind without one): the jobs' line, with the phase.
  c["summary"].erase("progress");
  c["progress"]["eta_seconds"] = 30;
  EXPECT_EQ(progress_line(c),
            "campaign 7 running [#######################.......] 75% 6/8 done, 2 running, 0 "
            "queued, ETA 30s  [2/4 budget]");
}

TEST(SweepSummary, JobCountsAndWhereTheResultsAre) {
  json c = running_calibration(390.0);
  c["kind"] = "sweep";
  c["state"] = "failed";
  c["progress"] = {{"total", 8},  {"queued", 0},    {"running", 0}, {"succeeded", 7},
                   {"failed", 1}, {"cancelled", 0}, {"cached", 2}};
  c.erase("summary");
  EXPECT_EQ(summary_text(c),
            "sweep 7 failed: 8 jobs, 7 succeeded (2 from the cache), 1 failed\n"
            "results: rockcal results 7 (--csv for one row per job)\n");
}

TEST(LinePacer, OneLinePerChangeAtMostEveryInterval) {
  LinePacer pacer(5s);
  const auto t0 = LinePacer::Clock::time_point{} + 1h;
  EXPECT_TRUE(pacer.due("a", t0));
  EXPECT_FALSE(pacer.due("a", t0 + 10s)) << "unchanged";
  EXPECT_FALSE(pacer.due("b", t0 + 4s)) << "changed, but too soon";
  EXPECT_TRUE(pacer.due("b", t0 + 5s));
  EXPECT_FALSE(pacer.due("b", t0 + 60s));
  EXPECT_TRUE(pacer.due("c", t0 + 60s));
}

}  // namespace
}  // namespace rockcal::api
