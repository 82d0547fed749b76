// The "auto" platen speed: it follows the bonds' failure strain, so a run is quasi-static by its
// reported measure whatever the strengths, and the peak load is homogeneous of degree 1 in them.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/loadtests/driver.hpp"
#include "engine/loadtests/loading_speed.hpp"
#include "engine/loadtests/quasi_static_rerun.hpp"
#include "engine/loadtests/specimen.hpp"

using namespace rockcal;
using nlohmann::json;

namespace {

// A tiny specimen of the default kind (seeded FCC, flattened disc), K_r 8000, nu 0.2.
JobSpec tiny(TestKind test, double fr0, double fs0) {
  JobSpec s;
  s.test = test;
  s.sample.diameter_m = 8;
  s.sample.height_m = 16;
  s.material.kr_n_m = 8000;
  s.bond = {fr0, fs0};
  s.loading.platen_velocity_m_s.reset();  // "auto"
  s.loading.max_strain = 0.1;
  return s;
}

std::string refusal(const json& loading) {
  json j = {{"test", "uct"},
            {"material", {{"kr", 8000}}},
            {"bond", {{"fr0", 64}, {"fs0", 64}}},
            {"loading", loading}};
  try {
    parse_job(j);
  } catch (const SpecError& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace

TEST(AutoSpeed, SpecTakesAutoWithItsTransitsAndKeepsNumbersAsTheyWere) {
  json j = {{"test", "uct"},
            {"material", {{"kr", 8000}}},
            {"bond", {{"fr0", 64}, {"fs0", 64}}},
            {"loading", {{"platen_velocity", "auto"}, {"auto_transits", 40}}}};
  const JobSpec s = parse_job(j);
  EXPECT_FALSE(s.loading.platen_velocity_m_s);
  EXPECT_EQ(s.loading.auto_transits, 40.0);
  const json c = to_json(s);
  EXPECT_EQ(c["loading"]["platen_velocity"], "auto");
  EXPECT_EQ(c["loading"]["auto_transits"], 40.0);
  EXPECT_EQ(c["loading"]["past_window"], "stop");
  EXPECT_EQ(parse_job(c), s);
  j["loading"]["past_window"] = "speed_up";
  EXPECT_TRUE(parse_job(j).loading.speed_up_past_window);
  EXPECT_EQ(parse_job(to_json(parse_job(j))), parse_job(j));
  // A numeric speed keeps the canonical form it had (no auto_transits key).
  j["loading"] = {{"platen_velocity", 0.05}};
  EXPECT_FALSE(to_json(parse_job(j))["loading"].contains("auto_transits"));
  EXPECT_EQ(refusal({{"platen_velocity", "fast"}}),
            "loading.platen_velocity: must be \"auto\" or a positive number");
  EXPECT_EQ(refusal({{"platen_velocity", 0.05}, {"auto_transits", 10}}),
            "loading.auto_transits: applies to platen_velocity \"auto\" only");
  EXPECT_EQ(refusal({{"platen_velocity", "auto"}, {"auto_transits", 0.5}}),
            "loading.auto_transits: must be in [1.0, 1000.0]");
  EXPECT_EQ(refusal({{"platen_velocity", 0.05}, {"past_window", "stop"}}),
            "loading.past_window: applies to platen_velocity \"auto\" only");
  EXPECT_EQ(refusal({{"platen_velocity", "auto"}, {"past_window", "slow"}}),
            "loading.past_window: must be \"stop\" or \"speed_up\"");
  // The follow speed: auto only, in the canonical form only when on (older jobs keep their ids).
  j["loading"] = {{"platen_velocity", "auto"}, {"follow_transits", 100}};
  EXPECT_EQ(parse_job(j).loading.follow_transits, 100.0);
  EXPECT_EQ(to_json(parse_job(j))["loading"]["follow_transits"], 100.0);
  EXPECT_EQ(parse_job(to_json(parse_job(j))), parse_job(j));
  j["loading"] = {{"platen_velocity", "auto"}};
  EXPECT_FALSE(to_json(parse_job(j))["loading"].contains("follow_transits"));
  EXPECT_EQ(refusal({{"platen_velocity", 0.05}, {"follow_transits", 100}}),
            "loading.follow_transits: applies to platen_velocity \"auto\" only");
  EXPECT_EQ(refusal({{"platen_velocity", "auto"}, {"follow_transits", 5}}),
            "loading.follow_transits: must be in [10.0, 10000.0]");
}

TEST(AutoSpeed, SpeedClosesTheBondFailureStrainInTheGivenTransits) {
  const JobSpec s = tiny(TestKind::uct, 64, 64);
  // K_s = K_r (1 - 3 nu) / (1 + nu) = K_r / 3 at nu 0.2: tension fails first, at F_r0 / K_r.
  EXPECT_DOUBLE_EQ(bond_failure_strain(s), 64.0 / 8000.0 / 2.0);
  EXPECT_DOUBLE_EQ(bond_failure_strain(tiny(TestKind::uct, 64, 8)), 3.0 * 8.0 / 8000.0 / 2.0);
  const double closure_time = bond_failure_strain(s) * 16.0 / (2.0 * platen_speed(s));
  EXPECT_DOUBLE_EQ(closure_time, 20.0 * wave_transit_time(s));
  // Proportional to the strengths: what keeps a run homogeneous in them.
  EXPECT_DOUBLE_EQ(platen_speed(tiny(TestKind::uct, 6.4, 6.4)), 0.1 * platen_speed(s));
  // The rate effect divides the transits, i.e. multiplies the speed.
  JobSpec fast = s;
  fast.effects["rate"] = {{"speed_factor", 4.0}};
  EXPECT_DOUBLE_EQ(platen_speed(effective_spec(fast)), 4.0 * platen_speed(s));
}

// A stiff rock (UCS/E about 1e-3: F 4 at K_r 8000) loaded at the seed's fixed 0.05 m/s reaches its
// peak within a few wave transits; the auto speed makes the same run quasi-static by the measure
// the result reports (the peak at least kQuasiStaticTransits transits after seating).
TEST(AutoSpeed, StiffRockIsQuasiStaticAtTheAutoSpeedAndNotAtTheFixedOne) {
  JobSpec s = tiny(TestKind::uct, 4, 4);
  const TestResult automatic = run_test(s);
  s.loading.platen_velocity_m_s = 0.05;
  const TestResult fixed = run_test(s);
  ASSERT_TRUE(automatic.peak_reached);
  ASSERT_TRUE(fixed.peak_reached);
  ASSERT_TRUE(automatic.loading_rate && fixed.loading_rate);
  EXPECT_TRUE(automatic.loading_rate->automatic);
  EXPECT_TRUE(automatic.loading_rate->quasi_static());
  EXPECT_GE(automatic.loading_rate->peak_transits, kQuasiStaticTransits);
  EXPECT_FALSE(automatic.loading_rate->late_peak);  // bond-controlled
  EXPECT_FALSE(fixed.loading_rate->quasi_static());
  EXPECT_LT(fixed.loading_rate->peak_transits, 10.0);
  // The particles move far more at the fixed speed's peak.
  EXPECT_GT(fixed.loading_rate->kinetic_energy_ratio,
            10.0 * automatic.loading_rate->kinetic_energy_ratio);
  RecordProperty("peak_transits_auto", std::to_string(automatic.loading_rate->peak_transits));
  RecordProperty("peak_transits_fixed", std::to_string(fixed.loading_rate->peak_transits));
}

// Scaling both strengths by 100 scales the peak load by 100^p with p within 0.1 of 1, for the UCT
// and the BTT, over the strengths of UCS/E about 2e-4 to 2e-2.
TEST(AutoSpeed, PeakLoadIsHomogeneousOfDegreeOneOverAHundredfoldStrengthRange) {
  for (TestKind test : {TestKind::uct, TestKind::btt}) {
    const TestResult weak = run_test(tiny(test, 0.64, 0.64));
    const TestResult strong = run_test(tiny(test, 64, 64));
    ASSERT_TRUE(weak.peak_reached) << to_string(test);
    ASSERT_TRUE(strong.peak_reached) << to_string(test);
    const double p = std::log(strong.peak_load_n / weak.peak_load_n) / std::log(100.0);
    EXPECT_NEAR(p, 1.0, 0.1) << to_string(test);
    RecordProperty(std::string("exponent_") + to_string(test), std::to_string(p));
  }
}

// The same with the follow speed setting the UCT's speed at its peak (F_s0 / F_r0 1.8, two-rate
// loading at auto_transits 10, follow_transits 100, as the calibration templates load): the
// follow speed scales with the closure, which scales with the strengths.
TEST(AutoSpeed, AFollowedPeakIsHomogeneousOfDegreeOneOverAHundredfoldStrengthRange) {
  auto followed = [](double scale) {
    JobSpec s = tiny(TestKind::uct, 0.25 * scale, 0.45 * scale);
    s.loading.auto_transits = 10;
    s.loading.slow_factor = 0.25;
    s.loading.follow_transits = 100;
    return run_test(s);
  };
  const TestResult weak = followed(1), strong = followed(100);
  ASSERT_TRUE(weak.peak_reached && strong.peak_reached);
  ASSERT_TRUE(weak.loading_rate && strong.loading_rate);
  EXPECT_TRUE(weak.loading_rate->followed);
  EXPECT_TRUE(strong.loading_rate->followed);
  const double p = std::log(strong.peak_load_n / weak.peak_load_n) / std::log(100.0);
  EXPECT_NEAR(p, 1.0, 0.1);
  RecordProperty("exponent", std::to_string(p));
}

// Where F_s0 exceeds F_r0 the UCT's peak comes many tensile failure strains in, so at the auto
// speed (two-rate, auto_transits 10) it takes hundreds of transits. Following the closure
// (follow_transits 100) reaches it in far fewer steps, with the follow speed setting the speed at
// the peak and the peak still past the quasi-static threshold; the BTT ignores it (its closure is
// mostly its contacts' indentation) and runs step for step as without.
TEST(AutoSpeed, FollowingTheClosureReachesALateUctPeakInFewerStepsAndLeavesTheBttAlone) {
  JobSpec s = tiny(TestKind::uct, 25, 45);
  s.loading.auto_transits = 10;
  s.loading.slow_factor = 0.25;
  const TestResult plain = run_test(s);
  s.loading.follow_transits = 100;
  const TestResult followed = run_test(s);
  ASSERT_TRUE(plain.peak_reached && followed.peak_reached);
  ASSERT_TRUE(plain.loading_rate && followed.loading_rate);
  EXPECT_FALSE(plain.loading_rate->followed);
  EXPECT_TRUE(followed.loading_rate->followed);
  EXPECT_EQ(followed.loading_rate->follow_transits, 100.0);
  EXPECT_TRUE(followed.loading_rate->quasi_static());
  EXPECT_LT(double(followed.steps), 0.7 * double(plain.steps));
  // The peak's closure grew at most e-fold per follow_transits transits past the auto speed's
  // reach: no sooner than 100 transits after seating.
  EXPECT_GE(followed.loading_rate->peak_transits, 100.0);
  EXPECT_NEAR(followed.peak_load_n / plain.peak_load_n, 1.0, 0.15);
  RecordProperty("steps_plain", std::to_string(plain.steps));
  RecordProperty("steps_followed", std::to_string(followed.steps));
  RecordProperty("peak_ratio", std::to_string(followed.peak_load_n / plain.peak_load_n));

  JobSpec disc = tiny(TestKind::btt, 25, 45);
  disc.loading.slow_factor = 0.25;
  const TestResult disc_plain = run_test(disc);
  disc.loading.follow_transits = 100;
  const TestResult disc_followed = run_test(disc);
  EXPECT_EQ(disc_followed.steps, disc_plain.steps);
  EXPECT_EQ(disc_followed.peak_load_n, disc_plain.peak_load_n);
  ASSERT_TRUE(disc_followed.loading_rate);
  EXPECT_FALSE(disc_followed.loading_rate->followed);
}

// A weak rock whose UCT is carried past its bonds' failure to large strains (compressed bonds,
// F_s0 = 3.64 F_r0): the auto speed holds for kBondControlledWindow failure strains, then speeds
// up, so the run's length is bounded by the window plus kLateTransits transits (at the weak
// rock's own auto speed, the 10% max_strain alone would take 20 x 0.1 / 4e-5 = 50,000 transits),
// and the result flags the peak as late.
TEST(AutoSpeed, PastTheBondControlledWindowThePlatensSpeedUpAndTheRunIsBounded) {
  JobSpec s = tiny(TestKind::uct, 0.64, 2.33);
  s.loading.speed_up_past_window = true;
  const TestResult r = run_test(s);
  ASSERT_TRUE(r.loading_rate);
  const LoadingRate& q = *r.loading_rate;
  EXPECT_DOUBLE_EQ(q.late_velocity_m_s, late_platen_speed(s));
  EXPECT_GT(q.late_velocity_m_s, 10.0 * q.platen_velocity_m_s);
  const double transit = wave_transit_time(s);
  const double window_s =
      kBondControlledWindow * bond_failure_strain(s) * 16.0 / (2.0 * q.platen_velocity_m_s);
  const double bound_s = window_s + (kLateTransits + 10.0) * transit;  // + seating and ramps
  EXPECT_LT(static_cast<double>(r.steps) * r.dt_s, bound_s);
  ASSERT_TRUE(r.peak_reached) << r.no_peak_reason;
  EXPECT_TRUE(q.late_peak);
  RecordProperty("steps", std::to_string(r.steps));
}

// The same weak rock at the default: the load still rises when the closure passes the
// bond-controlled window, so the run ends there without a peak and says why (a crushed
// specimen's load is not a strength), in fewer steps than the speeded-up run.
TEST(AutoSpeed, ByDefaultARunStillRisingPastTheWindowEndsThereWithoutAPeak) {
  JobSpec s = tiny(TestKind::uct, 0.64, 2.33);
  const TestResult stopped = run_test(s);
  s.loading.speed_up_past_window = true;
  const TestResult late = run_test(s);
  EXPECT_FALSE(stopped.peak_reached);
  EXPECT_EQ(stopped.stop_reason, "past_window");
  EXPECT_NE(stopped.no_peak_reason.find("still rising past the bond-controlled window"),
            std::string::npos)
      << stopped.no_peak_reason;
  ASSERT_TRUE(late.peak_reached);
  EXPECT_LT(stopped.steps, late.steps);
  // The window's closure: kBondControlledWindow failure strains of the loaded length (16).
  const double window = kBondControlledWindow * bond_failure_strain(s) * 16.0;
  ASSERT_FALSE(stopped.curve.empty());
  EXPECT_GE(stopped.curve.back().displacement_m, window);
  EXPECT_LT(stopped.curve.back().displacement_m, 1.1 * window);
  RecordProperty("steps_stopped", std::to_string(stopped.steps));
  RecordProperty("steps_speeded_up", std::to_string(late.steps));
}

// Where F_s0 is well below F_r0 the specimen fails after a few bond failures: at auto_transits 10
// this one's peak comes 24 transits after seating (at 40, 93). With loading.quasi_static_rerun the
// run goes again, slower by the factor that brings that peak past the threshold, and the result is
// the slower run's, quasi-static by its own measure, with the first run's peak and transits beside
// it.
TEST(AutoSpeed, ARunThatCameTooFastRunsAgainSlowerWithTheRerun) {
  JobSpec s = tiny(TestKind::uct, 40, 12);
  s.loading.auto_transits = 10;
  const TestResult once = run_test(s);
  ASSERT_TRUE(once.peak_reached && once.loading_rate);
  ASSERT_FALSE(once.loading_rate->quasi_static()) << once.loading_rate->peak_transits;
  EXPECT_FALSE(once.loading_rate->rerun);
  s.loading.quasi_static_rerun = true;
  const TestResult twice = run_test(s);
  ASSERT_TRUE(twice.peak_reached && twice.loading_rate);
  ASSERT_TRUE(twice.loading_rate->rerun);
  const QuasiStaticRerun& r = *twice.loading_rate->rerun;
  EXPECT_DOUBLE_EQ(r.first_peak_transits, once.loading_rate->peak_transits);
  EXPECT_DOUBLE_EQ(r.first_peak_load_n, once.peak_load_n);
  EXPECT_DOUBLE_EQ(r.auto_transits,
                   10 * std::min(kMaxRerunFactor, kRerunMargin * kQuasiStaticTransits /
                                                      once.loading_rate->peak_transits));
  EXPECT_TRUE(twice.loading_rate->quasi_static()) << twice.loading_rate->peak_transits;
  EXPECT_GT(twice.wall_seconds, once.wall_seconds);
  // The follow speed slows down with the rest: the rerun's follow_transits by the same factor.
  JobSpec followed = s;
  followed.loading.follow_transits = 100;
  const TestResult rerun = run_test(followed);
  ASSERT_TRUE(rerun.loading_rate && rerun.loading_rate->rerun);
  EXPECT_DOUBLE_EQ(rerun.loading_rate->follow_transits,
                   100 * rerun.loading_rate->rerun->auto_transits / 10);
  EXPECT_GT(rerun.loading_rate->follow_transits, 100.0);
  // A quasi-static run is not repeated.
  JobSpec slow = s;
  slow.loading.auto_transits = 40;
  const TestResult calm = run_test(slow);
  ASSERT_TRUE(calm.loading_rate);
  EXPECT_TRUE(calm.loading_rate->quasi_static());
  EXPECT_FALSE(calm.loading_rate->rerun);
  // The field: "auto" only, not with a rate study; absent from the canonical
  // form when off, so that earlier jobs keep their identities.
  EXPECT_EQ(refusal({{"platen_velocity", 0.05}, {"quasi_static_rerun", true}}),
            "loading.quasi_static_rerun: applies to platen_velocity \"auto\" only");
  EXPECT_EQ(refusal({{"platen_velocity", "auto"}, {"quasi_static_rerun", 1}}),
            "loading.quasi_static_rerun: must be true or false");
  EXPECT_EQ(
      refusal({{"platen_velocity", "auto"}, {"quasi_static_rerun", true}, {"rate_study", true}}),
      "loading.quasi_static_rerun: not with loading.rate_study (the study runs slower on its "
      "own)");
  // The elastic test takes the field (a calibration's template serves every test) and ignores it.
  json elastic = {{"test", "elastic"},
                  {"material", {{"kr", 8000}}},
                  {"bond", {{"fr0", 64}, {"fs0", 64}}},
                  {"loading", {{"platen_velocity", "auto"}, {"quasi_static_rerun", true}}}};
  EXPECT_TRUE(parse_job(elastic).loading.quasi_static_rerun);
  EXPECT_EQ(to_json(s)["loading"]["quasi_static_rerun"], true);
  EXPECT_EQ(parse_job(to_json(s)), s);
  slow.loading.quasi_static_rerun = false;
  EXPECT_FALSE(to_json(slow)["loading"].contains("quasi_static_rerun"));
}

// Fault injection: the slower run ends without a peak (max_strain). A slower run's largest load is
// not a strength, so the first run's peak stands, reported not quasi-static and without a rerun
// record, with both runs' wall time; a slower run that was cancelled is returned as it is.
namespace {
std::vector<TestResult> injected;  // the outcomes the fake run returns, in order
int injected_calls = 0;
TestResult injected_run(const JobSpec&, const RunHooks&) {
  return injected.at(std::size_t(injected_calls++));
}
TestResult outcome(bool peak, double load, double transits, const std::string& stop) {
  TestResult r;
  r.peak_reached = peak;
  r.peak_load_n = load;
  r.stop_reason = stop;
  r.wall_seconds = 1.5;
  r.loading_rate = LoadingRate{};
  r.loading_rate->peak_transits = transits;
  r.loading_rate->min_transits = kQuasiStaticTransits;
  return r;
}
}  // namespace

TEST(AutoSpeed, ASlowerRunWithoutAPeakLeavesTheFirstRunsPeak) {
  JobSpec s = tiny(TestKind::uct, 40, 12);
  s.loading.auto_transits = 10;
  s.loading.quasi_static_rerun = true;
  injected = {outcome(true, 100.0, 20.0, "post_peak"), outcome(false, 150.0, 0.0, "max_strain")};
  injected_calls = 0;
  const TestResult r = run_with_quasi_static_rerun(s, {}, injected_run);
  EXPECT_EQ(injected_calls, 2);
  EXPECT_TRUE(r.peak_reached);
  EXPECT_EQ(r.peak_load_n, 100.0);
  EXPECT_EQ(r.stop_reason, "post_peak");
  ASSERT_TRUE(r.loading_rate);
  EXPECT_FALSE(r.loading_rate->quasi_static());
  EXPECT_FALSE(r.loading_rate->rerun);
  EXPECT_EQ(r.wall_seconds, 3.0);
  // A cancelled slower run is the result: the campaign stops, no peak is claimed.
  injected = {outcome(true, 100.0, 20.0, "post_peak"), outcome(false, 40.0, 0.0, "cancelled")};
  injected_calls = 0;
  const TestResult cancelled = run_with_quasi_static_rerun(s, {}, injected_run);
  EXPECT_EQ(cancelled.stop_reason, "cancelled");
  EXPECT_FALSE(cancelled.peak_reached);
  // With a peak, the slower run replaces the first, which it records.
  injected = {outcome(true, 100.0, 20.0, "post_peak"), outcome(true, 90.0, 110.0, "post_peak")};
  injected_calls = 0;
  const TestResult slower = run_with_quasi_static_rerun(s, {}, injected_run);
  EXPECT_EQ(slower.peak_load_n, 90.0);
  ASSERT_TRUE(slower.loading_rate && slower.loading_rate->rerun);
  EXPECT_EQ(slower.loading_rate->rerun->first_peak_load_n, 100.0);
  EXPECT_EQ(slower.loading_rate->rerun->first_peak_transits, 20.0);
  EXPECT_EQ(slower.wall_seconds, 3.0);
}
