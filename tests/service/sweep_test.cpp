// The sweep planner validates a whole request before anything is stored, and job identity hashes
// ignore what does not change a result.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "db/store.hpp"
#include "orchestrator/campaign_status.hpp"
#include "orchestrator/job_identity.hpp"
#include "orchestrator/progress_model.hpp"
#include "orchestrator/request_error.hpp"
#include "orchestrator/sweep.hpp"
#include "support.hpp"

namespace rockcal::orch {
namespace {

using nlohmann::json;

std::string rejected_field(const json& request, Limits limits = {}) {
  try {
    plan_sweep(request, limits);
  } catch (const RequestError& e) {
    return e.field;
  }
  return "(accepted)";
}

json base() {
  return test::sweep_request({"uct", "btt"}, {50, 80}, {60, 90});
}

TEST(Sweep, OneJobPerPointAndTest) {
  auto plan = plan_sweep(base(), {});
  ASSERT_EQ(plan.jobs.size(), 8u);
  EXPECT_EQ(plan.name, "test sweep");
  EXPECT_EQ(plan.jobs[0].test, "uct");
  EXPECT_EQ(plan.jobs[0].fr0, 50);
  EXPECT_EQ(plan.jobs[1].fs0, 90);
  EXPECT_EQ(plan.jobs[7].test, "btt");
  json spec = json::parse(plan.jobs[3].spec);
  EXPECT_EQ(spec["bond"]["fr0"], 80.0);
  EXPECT_EQ(spec["bond"]["fs0"], 90.0);
  EXPECT_EQ(spec["sample"]["diameter"],
            test::sweep_request({"uct"}, {1}, {1})["job"]["sample"]["diameter"]);
}

TEST(Sweep, ExplicitPoints) {
  json r = base();
  r.erase("grid");
  r["points"] = {{10, 20}, {30, 40}, {50, 60}};
  EXPECT_EQ(plan_sweep(r, {}).jobs.size(), 6u);
}

TEST(Sweep, RejectsBadRequestsNamingTheField) {
  json r = base();
  r["colour"] = "red";
  EXPECT_EQ(rejected_field(r), "colour");
  r = base();
  r["tests"] = {"uct", "hydrostatic"};
  EXPECT_EQ(rejected_field(r), "tests[1]");
  r = base();
  r["tests"] = "uct";
  EXPECT_EQ(rejected_field(r), "tests");
  r = base();
  r["grid"]["fr0"] = {50, "80"};
  EXPECT_EQ(rejected_field(r), "grid.fr0[1]");
  r = base();
  r["grid"]["fs0"] = {std::numeric_limits<double>::quiet_NaN()};
  EXPECT_EQ(rejected_field(r), "grid.fs0[0]");
  r = base();
  r["grid"]["fs0"] = {-1};
  EXPECT_EQ(rejected_field(r), "grid.fs0[0]");
  r = base();
  r["grid"]["step"] = 3;
  EXPECT_EQ(rejected_field(r), "grid.step");
  r = base();
  r["points"] = {{1, 2}};
  EXPECT_EQ(rejected_field(r), "grid");  // both grid and points
  r = base();
  r["job"]["test"] = "uct";
  EXPECT_EQ(rejected_field(r), "job.test");
  r = base();
  r["job"]["sample"]["diameter"] = -6;
  EXPECT_EQ(rejected_field(r), "job.sample.diameter");
  r = base();
  r["job"]["material"]["nu"] = 0.4;
  EXPECT_EQ(rejected_field(r), "job.material.nu");
  r = base();
  r["job"]["loading"]["warp"] = 9;
  EXPECT_EQ(rejected_field(r), "job.loading.warp");
  r = base();
  r["name"] = 7;
  EXPECT_EQ(rejected_field(r), "name");
}

TEST(Sweep, EnormousGridsAreRefusedBeforeExpansion) {
  json r = base();
  std::vector<double> many(1000, 1.0);
  r["grid"] = {{"fr0", many}, {"fs0", many}};  // 10^6 points
  EXPECT_EQ(rejected_field(r), "grid");
  Limits small;
  small.max_jobs_per_campaign = 7;
  EXPECT_EQ(rejected_field(base(), small), "grid");  // 8 jobs > 7
  small.max_jobs_per_campaign = 8;
  EXPECT_EQ(rejected_field(base(), small), "(accepted)");
}

TEST(Identity, HashIgnoresOutputAndKeyOrderButNotPhysics) {
  json a = test::tiny_job_template();
  a["test"] = "uct";
  json b = json::parse(a.dump());  // same content
  b["output"] = {{"curve_points", 50}, {"progress_seconds", 0.5}};
  EXPECT_EQ(make_job(a).hash, make_job(b).hash);
  json defaults_spelled_out = a;
  defaults_spelled_out["contact"] = {{"friction", 0.6}};  // the default, written out
  EXPECT_EQ(make_job(a).hash, make_job(defaults_spelled_out).hash);
  json c = a;
  c["bond"]["fr0"] = 65;
  EXPECT_NE(make_job(a).hash, make_job(c).hash);
  json d = a;
  d["test"] = "btt";
  EXPECT_NE(make_job(a).hash, make_job(d).hash);
  EXPECT_EQ(make_job(a).hash.size(), 64u);
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(CampaignState, DerivedFromJobCounts) {
  db::CampaignRow c;
  db::StateCounts n;
  n.queued = 3;
  EXPECT_EQ(derive_state(n, c), "queued");
  n.running = 1;
  EXPECT_EQ(derive_state(n, c), "running");
  n = {};
  n.succeeded = 2;
  EXPECT_EQ(derive_state(n, c), "succeeded");
  n.failed = 1;
  EXPECT_EQ(derive_state(n, c), "failed");
  c.cancel_requested = true;
  n.cancelled = 1;
  EXPECT_EQ(derive_state(n, c), "cancelled");
  db::CampaignRow driven;
  driven.driver_status = "running";
  EXPECT_EQ(derive_state({}, driven), "running");
  driven.driver_status = "done";
  n = {};
  n.succeeded = 80;
  n.failed = 3;  // runs without a peak, which the calibration took as failed evaluations
  EXPECT_EQ(derive_state(n, driven), "succeeded");
  driven.driver_status = "failed";
  EXPECT_EQ(derive_state(n, driven), "failed");
}

// A driver adds jobs as it goes, so the share of its jobs done can fall; the campaign's fraction
// is its progress model's instead: a diagnosis's jobs done (counted as the status is read) of the
// jobs it plans, or a calibration's model as it states it, and never goes backwards.
TEST(CampaignProgress, ADriversModelNotItsJobShareAndNeverBackwards) {
  test::TempDir dir;
  db::Store store{(dir.path() / "s.db").string()};
  auto new_job = [](int k) {
    return db::NewJob{"uct", double(k + 1), 1, "{}", "hash" + std::to_string(k)};
  };
  const std::int64_t id =
      store.create_campaign("diagnosis", "d", "{}", true, {new_job(0), new_job(1)});
  auto finish_one = [&] {
    const auto j = store.claim_job("local");
    ASSERT_TRUE(j);
    db::ResultRow r;
    r.hash = j->hash;
    r.job_id = j->id;
    r.test = j->test;
    r.fr0 = j->fr0;
    r.fs0 = j->fs0;
    r.peak_load = 1.0;
    r.engine_version = "v";
    r.result = "{}";
    ASSERT_TRUE(store.finish_success(j->id, r));
  };
  auto status = [&] { return campaign_status(store, *store.campaign(id), 1); };
  // What the diagnosis states at a phase: the jobs it plans by phase, and those done so far.
  auto phase = [&](int step, int done) {
    const json model = progress_model_json(
        "jobs", done, {{"grid", 2}, {"budget", 4}, {"confirm", 2}}, 0, std::nullopt, false);
    store.set_driver_status(
        id, "running",
        json{{"phase", "p"}, {"step", step}, {"steps", 4}, {"progress", model}}.dump());
  };
  phase(1, 0);
  EXPECT_EQ(status().fraction, 0.0);
  finish_one();
  EXPECT_EQ(status().fraction, 0.125) << "counted as it is read, not when the phase began";
  finish_one();
  EXPECT_EQ(status().fraction, 0.25);  // the jobs' share is 1 here
  // The next phase adds 4 jobs: the jobs' share falls to 2 of 6, the campaign's does not.
  for (int k = 2; k < 6; ++k) store.add_job(id, new_job(k));
  phase(2, 2);
  EXPECT_EQ(status().fraction, 0.25);
  finish_one();
  const CampaignStatus now = status();
  EXPECT_EQ(now.fraction, 0.375);
  EXPECT_EQ(now.model["done"], 3);
  EXPECT_EQ(now.model["budget"], 8);
  EXPECT_EQ(now.model["left"], 5);
  EXPECT_EQ(now.model["parts"], json::parse(R"([{"name": "grid", "budget": 2},
    {"name": "budget", "budget": 4}, {"name": "confirm", "budget": 2}])"));
  // A calibration states its whole model (its evaluations of the budget), taken as it is.
  const json calibration = {
      {"unit", "evaluations"}, {"done", 4}, {"budget", 10}, {"fraction", 0.4}};
  store.set_driver_status(id, "running", json{{"progress", calibration}}.dump());
  EXPECT_EQ(status().fraction, 0.4);
  EXPECT_EQ(status().model, calibration);
  // Once the driver has ended, its report carries the finished model and the status none.
  store.set_driver_status(id, "done", json{{"progress", calibration}}.dump());
  EXPECT_TRUE(status().model.is_null());
}

}  // namespace
}  // namespace rockcal::orch
