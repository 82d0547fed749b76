// Ensembles on their own: the statistics of a set of realisations, how a sweep expands
// "realisations" into one job per seed (and refuses what it cannot run, naming the field), how the
// store keeps a run without a peak as a failed job (new runs, the cache, and runs stored before),
// and the readable results table.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "api/cli/client.hpp"
#include "db/migrations.hpp"
#include "db/store.hpp"
#include "orchestrator/ensemble.hpp"
#include "orchestrator/job_files.hpp"
#include "orchestrator/job_identity.hpp"
#include "orchestrator/realisations.hpp"
#include "orchestrator/request_error.hpp"
#include "orchestrator/sweep.hpp"
#include "support.hpp"

namespace rockcal::orch {
namespace {

using nlohmann::json;

Realisation succeeded(std::uint64_t seed, double peak, double strength,
                      std::optional<double> modulus) {
  return {seed, std::int64_t(seed) + 100, "succeeded", peak, strength, modulus, ""};
}

TEST(EnsembleStats, MeanSampleSdAndStandardError) {
  const SampleStats s = sample_stats({50, 51, 52, 53, 54});
  EXPECT_EQ(s.n, 5);
  EXPECT_EQ(s.mean, 52.0);
  EXPECT_EQ(s.sd, std::sqrt(2.5));  // sum of squares 10 over n - 1 = 4
  EXPECT_DOUBLE_EQ(*s.se, std::sqrt(0.5));
  const SampleStats one = sample_stats({7});
  EXPECT_EQ(one.n, 1);
  EXPECT_EQ(one.mean, 7.0);
  EXPECT_FALSE(one.sd) << "one value has no spread";
  EXPECT_FALSE(one.se);
  const SampleStats none = sample_stats({});
  EXPECT_EQ(none.n, 0);
  EXPECT_FALSE(none.mean);
  EXPECT_EQ(to_json(none), json::parse(R"({"mean": null, "sd": null, "se": null, "n": 0})"));
}

TEST(EnsembleStats, FailedRealisationsAreListedCountedAndLeftOut) {
  std::vector<Realisation> runs = {
      succeeded(5, 71, 68, std::nullopt), {2, 102, "failed", {}, {}, {}, "no peak: no bond broke"},
      succeeded(1, 67, 60, std::nullopt), {4, 104, "cancelled", {}, {}, {}, "cancelled"},
      {6, 106, "queued", {}, {}, {}, ""}, succeeded(3, 69, 64, std::nullopt)};
  const Ensemble e = make_ensemble(runs);
  ASSERT_EQ(e.realisations.size(), 6u);
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(e.realisations[i].seed, i + 1) << "seed order";
  EXPECT_EQ(e.failed, 2);
  EXPECT_EQ(e.peak_load.n, 3);
  EXPECT_EQ(e.peak_load.mean, 69.0);
  EXPECT_EQ(e.peak_load.sd, 2.0);
  EXPECT_DOUBLE_EQ(*e.peak_load.se, 2.0 / std::sqrt(3.0));
  EXPECT_EQ(e.strength.mean, 64.0);
  EXPECT_EQ(e.strength.sd, 4.0);
  EXPECT_EQ(e.modulus.n, 0) << "a BTT measures no modulus";
  const json j = to_json(e);
  EXPECT_EQ(j["failed"], 2);
  EXPECT_EQ(j["peak_load"]["n"], 3);
  EXPECT_EQ(j["modulus"]["mean"], nullptr);
  EXPECT_EQ(j["realisations"][1], json::parse(R"({"seed": 2, "job_id": 102, "state": "failed",
      "peak_load_n": null, "strength_pa": null, "youngs_modulus_pa": null,
      "quasi_static": null, "poisson_ratio": null, "error": "no peak: no bond broke"})"));
  EXPECT_EQ(j["realisations"][0]["peak_load_n"], 67.0);
  EXPECT_EQ(j["realisations"][0]["error"], nullptr);
}

// A run's own quasi-static verdict travels with its realisation (what a calibration's verdict
// counts), and a run that reported none has none.
TEST(EnsembleStats, ARealisationCarriesItsRunsQuasiStaticVerdict) {
  JobOutcome outcome;
  outcome.job_id = 7;
  outcome.state = "succeeded";
  outcome.result = db::ResultRow{};
  outcome.result->peak_load = 100.0;
  outcome.result->result = R"({"loading_rate": {"quasi_static": false, "peak_transits": 12}})";
  EXPECT_EQ(realisation(outcome, 3).quasi_static, std::optional<bool>(false));
  outcome.result->result = R"({"loading_rate": {"quasi_static": true}})";
  EXPECT_EQ(realisation(outcome, 3).quasi_static, std::optional<bool>(true));
  outcome.result->result = R"({"peak_reached": true})";
  EXPECT_FALSE(realisation(outcome, 3).quasi_static);
  outcome.result->result = R"({"loading_rate": {"quasi_static": null}})";
  EXPECT_FALSE(realisation(outcome, 3).quasi_static);
}

TEST(EnsembleStats, RealisationSeedsAndWhatCannotBeRun) {
  EXPECT_EQ(realisation_seeds(7, 3), (std::vector<std::uint64_t>{7, 8, 9}));
  EXPECT_FALSE(realisations_problem(5, 1, true));
  EXPECT_FALSE(realisations_problem(1, 1, false)) << "one run of any specimen is fine";
  EXPECT_EQ(realisations_problem(2, 1, false),
            "the template's specimen is the same under every seed (an aligned FCC lattice without "
            "seeded effects): more than one realisation would repeat one run");
  const std::uint64_t largest = 9223372036854775807ull;
  EXPECT_FALSE(realisations_problem(1, largest, true));
  EXPECT_EQ(realisations_problem(2, largest, true),
            "sample.seed + realisations - 1 exceeds the largest seed, 9223372036854775807");
}

json random_template() {
  json t = test::tiny_job_template();
  t["sample"]["packing"] = "random";
  return t;
}

json ensemble_sweep(const json& realisations) {
  json r = test::sweep_request({"uct", "btt"}, {50}, {60, 70});
  r["job"] = random_template();
  r["realisations"] = realisations;
  return r;
}

std::uint64_t seed_of(const db::NewJob& job) {
  return json::parse(job.spec)["sample"]["seed"].get<std::uint64_t>();
}

TEST(SweepRealisations, OneJobPerSeedWithItsOwnIdentity) {
  json r = ensemble_sweep(3);
  r["job"]["sample"]["seed"] = 11;
  const CampaignPlan plan = plan_sweep(r, {});
  ASSERT_EQ(plan.jobs.size(), 2u * 2u * 3u);
  std::set<std::string> hashes;
  for (std::size_t i = 0; i < plan.jobs.size(); ++i) {
    EXPECT_EQ(seed_of(plan.jobs[i]), 11 + i % 3) << i;
    hashes.insert(plan.jobs[i].hash);
  }
  EXPECT_EQ(hashes.size(), plan.jobs.size());
  EXPECT_EQ(plan.jobs[3].test, "uct");
  EXPECT_EQ(plan.jobs[3].fs0, 70.0);
  EXPECT_EQ(plan.jobs[6].test, "btt");
  // Realisation k is the job a template with seed s + k makes: what lets 5 reuse 3's runs.
  json shifted = r;
  shifted["job"]["sample"]["seed"] = 12;
  shifted["realisations"] = 1;
  EXPECT_EQ(plan_sweep(shifted, {}).jobs[0].hash, plan.jobs[1].hash);
  // One realisation is exactly the sweep without the field (old requests keep their identities).
  json plain = ensemble_sweep(1);
  const CampaignPlan one = plan_sweep(plain, {});
  plain.erase("realisations");
  const CampaignPlan none = plan_sweep(plain, {});
  ASSERT_EQ(one.jobs.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(one.jobs[i].hash, none.jobs[i].hash);
  EXPECT_EQ(seed_of(one.jobs[0]), 1u) << "the engine's default seed";
}

std::pair<std::string, std::string> refusal(const json& request, Limits limits = {}) {
  try {
    plan_sweep(request, limits);
  } catch (const RequestError& e) {
    return {e.field, e.message};
  }
  return {"(accepted)", ""};
}

TEST(SweepRealisations, BadCountsAreRefusedNamingTheField) {
  const std::pair<std::string, std::string> range = {"realisations",
                                                     "must be an integer in [1, 100]"};
  for (const json& bad : {json(0), json(-2), json(101), json(2.5), json("3"), json(true),
                          json(nullptr), json::array({3})}) {
    EXPECT_EQ(refusal(ensemble_sweep(bad)), range) << bad.dump();
  }
  EXPECT_EQ(refusal(ensemble_sweep(100)).first, "(accepted)");
  // The cap counts every realisation: 2 tests x 2 points x 3 = 12 jobs.
  Limits small;
  small.max_jobs_per_campaign = 11;
  EXPECT_EQ(refusal(ensemble_sweep(3), small),
            std::make_pair(std::string("grid"),
                           std::string("12 jobs exceed the cap of 11 per campaign")));
  small.max_jobs_per_campaign = 12;
  EXPECT_EQ(refusal(ensemble_sweep(3), small).first, "(accepted)");
  // An aligned FCC lattice without seeded effects is one specimen whatever the seed.
  json fcc = ensemble_sweep(2);
  fcc["job"]["sample"]["packing"] = "fcc";
  fcc["job"]["sample"]["lattice"] = "aligned";
  EXPECT_EQ(refusal(fcc),
            std::make_pair(std::string("realisations"),
                           std::string("the template's specimen is the same under every seed (an "
                                       "aligned FCC lattice without seeded effects): more than one "
                                       "realisation would repeat one run")));
  fcc["job"]["sample"].erase("lattice");
  EXPECT_EQ(refusal(fcc).first, "(accepted)") << "a seeded lattice (the default) is another cut";
  fcc["job"]["sample"]["lattice"] = "aligned";
  fcc["job"]["effects"] = {{"heterogeneity", {{"weibull_m", 4.0}}}};
  EXPECT_EQ(refusal(fcc).first, "(accepted)") << "a seeded effect makes the seed matter";
  json high = ensemble_sweep(2);
  high["job"]["sample"]["seed"] = 9223372036854775807ll;
  EXPECT_EQ(refusal(high).first, "realisations");
}

}  // namespace
}  // namespace rockcal::orch

namespace rockcal::db {
namespace {

using nlohmann::json;

ResultRow row_from(const JobRow& job, const json& result) {
  ResultRow r;
  r.hash = job.hash;
  r.job_id = job.id;
  r.test = job.test;
  r.fr0 = job.fr0;
  r.fs0 = job.fs0;
  r.no_peak = orch::no_peak_reason(result);
  if (!r.no_peak) r.peak_load = result["peak_load"].get<double>();
  r.result = result.dump();
  return r;
}

TEST(NoPeak, TheRuleReadsPeakReachedAndItsReason) {
  EXPECT_FALSE(orch::no_peak_reason(json::parse(R"({"test": "uct", "peak_reached": true})")));
  EXPECT_FALSE(orch::no_peak_reason(json::parse(R"({"test": "uct"})"))) << "older engines";
  EXPECT_EQ(orch::no_peak_reason(json::parse(
                R"({"test": "btt", "peak_reached": false, "no_peak_reason": "no bond broke"})")),
            "no bond broke");
  EXPECT_EQ(orch::no_peak_reason(json::parse(
                R"({"test": "uct", "peak_reached": false, "stop_reason": "max_strain"})")),
            "the run stopped (max_strain) before a peak");
  // The elastic test loads below failure: the engine writes no peak_reached for it.
  EXPECT_FALSE(
      orch::no_peak_reason(json::parse(R"({"test": "elastic", "stop_reason": "settled"})")));
}

TEST(NoPeak, ARunWithoutAPeakIsAFailedJobAndTheCacheSaysSo) {
  test::TempDir dir;
  Store store((dir.path() / "s.db").string());
  const std::vector<NewJob> jobs = {{"uct", 1, 2, "{}", "h"}, {"uct", 1, 2, "{}", "h"}};
  const std::int64_t first = store.create_campaign("sweep", "a", "{}", false, jobs);
  auto claimed = store.claim_job("local");
  ASSERT_TRUE(claimed);
  EXPECT_FALSE(store.claim_job("local")) << "its twin waits for it";
  const json result = {{"test", "uct"},
                       {"peak_load", 40.0},
                       {"peak_reached", false},
                       {"no_peak_reason", "the load rose on a loose particle"}};
  ASSERT_TRUE(store.finish_success(claimed->id, row_from(*claimed, result)));
  const std::string error = "no peak: the load rose on a loose particle";
  for (const auto& row : store.campaign_results(first)) {
    EXPECT_EQ(row.job.state, "failed");
    EXPECT_EQ(row.job.error, error);
    EXPECT_FALSE(row.result) << "a failed job has no result row in a results table";
  }
  EXPECT_EQ(store.job(claimed->id)->attempts, 1) << "not retried";
  // The run is kept for inspection, without values.
  const auto kept = store.result("h");
  ASSERT_TRUE(kept);
  EXPECT_EQ(kept->no_peak, "the load rose on a loose particle");
  EXPECT_FALSE(kept->peak_load);
  EXPECT_EQ(json::parse(kept->result)["peak_load"], 40.0);
  // Asking again answers from the store: failed, cached, the same reason, nothing queued.
  const std::int64_t again = store.create_campaign("sweep", "b", "{}", false, {jobs[0]});
  const auto rows = store.campaign_results(again);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].job.state, "failed");
  EXPECT_TRUE(rows[0].job.cached);
  EXPECT_EQ(rows[0].job.error, error);
  EXPECT_FALSE(store.claim_job("local"));
}

// A database written before the rule (migration 1): stored runs that said "peak_reached": false
// become failed jobs without values, so neither a listing nor the cache serves their number.
TEST(NoPeak, RunsStoredBeforeTheRuleAreJudgedByIt) {
  test::TempDir dir;
  const std::string path = (dir.path() / "old.db").string();
  {
    Connection c(path);
    c.exec("CREATE TABLE schema_version (version INTEGER NOT NULL)");
    c.exec(migrations().front().sql);
    c.exec("INSERT INTO schema_version (version) VALUES (1)");
    c.exec(
        "INSERT INTO campaigns (kind, name, request, created_at) VALUES ('sweep', 'old', '{}', 0)");
    const char* insert_job =
        "INSERT INTO jobs (campaign_id, test, fr0, fs0, spec, hash, state, created_at) "
        "VALUES (1, ?, 1, 2, '{}', ?, 'succeeded', 0)";
    const char* insert_result =
        "INSERT INTO results (hash, job_id, test, fr0, fs0, peak_load, strength, engine_version, "
        "result, created_at) VALUES (?, ?, ?, 1, 2, 900, 3, 'v', ?, 0)";
    const std::vector<std::tuple<std::string, std::string, std::string>> runs = {
        {"cut", "uct", R"({"test": "uct", "peak_reached": false, "stop_reason": "max_strain"})"},
        {"said", "btt",
         R"({"test": "btt", "peak_reached": false, "no_peak_reason": "no bond broke"})"},
        {"peak", "uct", R"({"test": "uct", "peak_reached": true, "stop_reason": "post_peak"})"},
        {"elastic", "elastic",
         R"({"test": "elastic", "peak_reached": false, "stop_reason": "settled"})"}};
    std::int64_t id = 0;
    for (const auto& [hash, test, result] : runs) {
      c.prepare(insert_job).bind_all(test, hash).run();
      c.prepare(insert_result).bind_all(hash, ++id, test, result).run();
    }
  }
  Store store(path);
  const auto rows = store.campaign_results(1);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].job.state, "failed");
  EXPECT_EQ(rows[0].job.error, "no peak: the run stopped (max_strain) before a peak");
  EXPECT_EQ(rows[1].job.state, "failed");
  EXPECT_EQ(rows[1].job.error, "no peak: no bond broke");
  EXPECT_EQ(store.result("cut")->no_peak, "the run stopped (max_strain) before a peak");
  EXPECT_FALSE(store.result("cut")->peak_load);
  EXPECT_FALSE(store.result("said")->strength);
  for (std::size_t i : {2u, 3u}) {
    EXPECT_EQ(rows[i].job.state, "succeeded") << i;
    ASSERT_TRUE(rows[i].result) << i;
    EXPECT_EQ(rows[i].result->peak_load, 900.0) << i;
    EXPECT_FALSE(rows[i].result->no_peak) << i;
  }
}

}  // namespace
}  // namespace rockcal::db

namespace rockcal::api {
namespace {

using nlohmann::json;

TEST(ResultsText, OneRowPerPointWithMeanStandardErrorAndTheRunsLeftOut) {
  const json body = json::parse(R"({"points": [
    {"test": "uct", "fr0": 50, "fs0": 60, "failed": 0,
     "peak_load": {"mean": 52, "sd": 1.58, "se": 0.7071, "n": 5},
     "strength": {"mean": 64, "sd": 3.16, "se": 1.414, "n": 5},
     "modulus": {"mean": 1020, "sd": 15.8, "se": 7.071, "n": 5},
     "realisations": []},
    {"test": "btt", "fr0": 67, "fs0": 60, "failed": 1,
     "peak_load": {"mean": 67, "sd": null, "se": null, "n": 1},
     "strength": {"mean": 60, "sd": null, "se": null, "n": 1},
     "modulus": {"mean": null, "sd": null, "se": null, "n": 0},
     "realisations": [{"seed": 1, "job_id": 7, "error": null},
                      {"seed": 2, "job_id": 8, "error": "no peak: no bond broke\nlog line"}]}]})");
  EXPECT_EQ(results_text(body),
            "test        fr0 (N)    fs0 (N)   n failed  peak_load (N, mean ± se)  "
            "strength (Pa, mean ± se)  youngs_modulus (Pa, mean ± se)\n"
            "uct              50         60   5      0  52 ± 0.707                "
            "64 ± 1.41                 1020 ± 7.07\n"
            "btt              67         60   1      1  67                        "
            "60                        -\n"
            "runs without values (left out of the statistics):\n"
            "  btt 67/60 seed 2 (job 8): no peak: no bond broke\n");
}

}  // namespace
}  // namespace rockcal::api
