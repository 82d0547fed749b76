// The effects of the sim-to-real gap diagnosis: each does what it says, and only that.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <tuple>
#include <utility>

#include "engine/confinement.hpp"
#include "engine/contacts.hpp"
#include "engine/domain.hpp"
#include "engine/effects/effect.hpp"
#include "engine/loadtests/specimen.hpp"
#include "tests/engine/bond_fixture.hpp"

using namespace rockcal;
using rockcal::testing::Pair;
using rockcal::testing::rot;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// An FCC cylinder of some 500 particles and 2,500 bonds: enough for statistics, built in
// milliseconds.
JobSpec cylinder(std::map<std::string, EffectValues> effects = {}) {
  JobSpec s;
  s.test = TestKind::uct;
  s.sample.diameter_m = 12;
  s.sample.height_m = 24;
  s.material.kr_n_m = 8000;
  s.effects = std::move(effects);
  return s;
}

using BondKey = std::pair<std::int64_t, std::int64_t>;
std::map<BondKey, Bond> by_ids(const std::vector<Bond>& bonds) {
  std::map<BondKey, Bond> out;
  for (const Bond& b : bonds) out.emplace(BondKey{b.id_i, b.id_j}, b);
  return out;
}

double weibull_cov(double m) {
  const double g1 = std::tgamma(1 + 1 / m), g2 = std::tgamma(1 + 2 / m);
  return std::sqrt(g2 / (g1 * g1) - 1);
}

struct Stats {
  double mean, cov;
};
Stats multiplier_stats(double m, std::uint64_t seed) {
  JobSpec base = cylinder(), het = cylinder({{"heterogeneity", {{"weibull_m", m}}}});
  base.sample.seed = het.sample.seed = seed;
  const auto plain = by_ids(make_specimen(base).bonds);
  const Simulation sim = make_specimen(het);
  EXPECT_EQ(sim.bonds.size(), plain.size());
  double sum = 0, sum2 = 0;
  for (const Bond& b : sim.bonds) {
    const Bond& p = plain.at({b.id_i, b.id_j});
    const double w = b.fr0 / p.fr0;
    EXPECT_NEAR(b.fs0 / p.fs0, w, 1e-12);  // one multiplier for all four strengths
    EXPECT_NEAR(b.gb0 / p.gb0, w, 1e-12);
    EXPECT_NEAR(b.gt0 / p.gt0, w, 1e-12);
    sum += w;
    sum2 += w * w;
  }
  const double n = static_cast<double>(sim.bonds.size());
  const double mean = sum / n;
  return {mean, std::sqrt(sum2 / n - mean * mean) / mean};
}

// Mean number of other cut bonds whose midpoint lies within 1.5 radii of a cut bond's midpoint:
// about 0.75 for cuts scattered at 10%, several when they lie on crack discs.
double cut_neighbours(const Simulation& sim) {
  std::vector<Vec3> mid;
  for (const Bond& b : sim.broken)
    mid.push_back(0.5 * (sim.particles.pos[b.i] + sim.particles.pos[b.j]));
  double pairs = 0;
  for (std::size_t a = 0; a < mid.size(); ++a)
    for (std::size_t b = 0; b < mid.size(); ++b)
      if (a != b && (mid[a] - mid[b]).norm() < 1.5) ++pairs;
  return pairs / static_cast<double>(mid.size());
}

// Two unit particles at x_i and x_j (ids 0 and 1) with the pair's bond intact or broken, and the
// effects applied as make_specimen would.
Simulation pair_sim(const Pair& p, const Vec3& x_j, bool intact,
                    std::map<std::string, EffectValues> effects) {
  Simulation sim;
  sim.particles.add(p.xi, 1.0, 1.0, 0.4, 0);
  sim.particles.add(x_j, 1.0, 1.0, 0.4, 1);
  (intact ? sim.bonds : sim.broken).push_back(p.bond);
  sim.contact = ContactLaw{p.k.kr_n_m, p.k.ks_n_m, 0.6, 0.6};
  sim.dt = 1e-3;
  sim.neighbours.skin = 0.5;
  JobSpec job;
  job.effects = std::move(effects);
  apply_specimen_effects(sim, effective_spec(job));
  return sim;
}

std::size_t broken_pairs(const Simulation& sim) {
  std::size_t n = 0;
  for (const ContactPair& c : sim.neighbours.pairs) n += c.bond == PairBond::broken;
  return n;
}

}  // namespace

TEST(Effects, RegistryMatchesTheDiagnosisTable) {
  struct Row {
    const char* name;
    const char* param;
    double neutral, strong;
    bool log_scale;
  };
  const Row table[] = {{"heterogeneity", "weibull_m", kInf, 2, false},
                       {"packing", "radius_ratio", 1, 2, false},
                       {"platen_friction", "mu", 0, 0.5, false},
                       {"flaws", "fraction", 0, 0.15, false},
                       {"rate", "speed_factor", 1, 8, true},
                       {"compression_coupling", "coupling", 1, 0, false},
                       {"post_break_friction", "mu", 0.6, 0.05, false},
                       {"interaction_range", "factor", 1, 1.5, false},
                       {"rolling_resistance", "mu_r", 0, 0.3, false},
                       {"brazilian_flats", "angle_deg", 30, 10, false}};
  ASSERT_EQ(effect_registry().size(), std::size(table));
  for (const Row& row : table) {
    const EffectDef* e = find_effect(row.name);
    ASSERT_NE(e, nullptr) << row.name;
    ASSERT_FALSE(e->params.empty());
    EXPECT_LE(e->params.size(), 2u);
    ASSERT_EQ(e->defaults.size(), e->params.size()) << row.name;
    EXPECT_EQ(e->params[0].name, row.param);
    EXPECT_EQ(e->params[0].neutral, row.neutral) << row.name;
    EXPECT_EQ(e->params[0].strong, row.strong) << row.name;
    EXPECT_EQ(e->params[0].log_scale, row.log_scale) << row.name;
    for (std::size_t k = 0; k < e->params.size(); ++k) {
      EXPECT_GE(e->defaults[k], e->params[k].lo) << row.name;
      EXPECT_LE(e->defaults[k], e->params[k].hi) << row.name;
    }
    EXPECT_TRUE(e->apply_spec || e->apply_specimen) << row.name;
  }
  EXPECT_EQ(find_effect("gravity"), nullptr);
}

TEST(Effects, ValueAtWalksFromNeutralToStrong) {
  const EffectDef& het = *find_effect("heterogeneity");
  EXPECT_TRUE(std::isinf(effect_value_at(het, 0.0)));  // off
  EXPECT_DOUBLE_EQ(effect_value_at(het, 1.0), 2.0);
  EXPECT_DOUBLE_EQ(effect_value_at(het, 0.5), 4.0);    // 1/m linear: halfway to 1/2
  EXPECT_DOUBLE_EQ(effect_value_at(het, 0.01), 50.0);  // clamped into the range a job accepts
  const EffectDef& rate = *find_effect("rate");
  EXPECT_DOUBLE_EQ(effect_value_at(rate, 0.0), 1.0);
  EXPECT_NEAR(effect_value_at(rate, 0.5), std::sqrt(8.0), 1e-12);  // log scale
  EXPECT_DOUBLE_EQ(effect_value_at(rate, 2.0), 8.0);               // s clamped to [0, 1]
  const EffectDef& coupling = *find_effect("compression_coupling");
  EXPECT_DOUBLE_EQ(effect_value_at(coupling, 0.25), 0.75);
  // A job-dependent neutral: the job's contact friction.
  const EffectDef& pbf = *find_effect("post_break_friction");
  JobSpec job;
  job.contact.friction = 0.4;
  EXPECT_DOUBLE_EQ(effect_value_at(pbf, 0.0, job), 0.4);
  EXPECT_DOUBLE_EQ(effect_value_at(pbf, 1.0, job), 0.05);
  EXPECT_DOUBLE_EQ(effect_value_at(pbf, 0.0), 0.6);  // the default job's
  // effect_walk_fraction is the walk's inverse, on every scale.
  for (const EffectDef& e : effect_registry()) {
    for (double s : {0.2, 0.5, 1.0}) {
      EXPECT_NEAR(effect_walk_fraction(e, effect_value_at(e, s, job), job), s, 1e-9) << e.name;
    }
  }
}

TEST(Effects, SpecHooksChangeTheEffectiveSpecOnly) {
  JobSpec job = cylinder({{"rate", {}}, {"platen_friction", {{"mu", 0.25}}}, {"packing", {}}});
  const JobSpec run = effective_spec(job);
  EXPECT_DOUBLE_EQ(*run.loading.platen_velocity_m_s, 4 * *job.loading.platen_velocity_m_s);
  EXPECT_DOUBLE_EQ(run.loading.platen_friction, 0.25);
  EXPECT_EQ(run.sample.packing, "random");
  EXPECT_DOUBLE_EQ(run.sample.radius_ratio, 1.5);
  EXPECT_TRUE(run.spec_effects_applied);
  EXPECT_EQ(effective_spec(run), run);  // idempotent: the rate is not compounded
  EXPECT_EQ(job.loading.platen_velocity_m_s, LoadingSpec{}.platen_velocity_m_s);  // as written
  EXPECT_THROW(to_json(run), std::logic_error);  // would apply the effects twice when parsed
  // The specimen follows the effective spec whichever form it is given.
  job = cylinder({{"platen_friction", {{"mu", 0.25}}}});
  const Simulation sim = make_specimen(job);
  EXPECT_DOUBLE_EQ(sim.walls[kBottomPlaten].friction, 0.25);
  EXPECT_DOUBLE_EQ(make_specimen(cylinder()).walls[kTopPlaten].friction, 0.0);
}

TEST(Effects, PackingSwitchesToARandomPacking) {
  JobSpec job = cylinder({{"packing", {{"radius_ratio", 2.0}}}});
  job.sample.diameter_m = 10;  // smaller random cuts lose most grains as floaters
  job.sample.height_m = 12;
  const Simulation sim = make_specimen(job);
  double r_min = kInf, r_max = 0;
  for (std::size_t k = 0; k < sim.particles.n_owned; ++k) {
    r_min = std::min(r_min, sim.particles.radius[k]);
    r_max = std::max(r_max, sim.particles.radius[k]);
  }
  EXPECT_GT(r_max / r_min, 1.5);  // FCC would be monodisperse
  EXPECT_LE(r_max / r_min, 2.0 + 1e-9);
}

TEST(Effects, TheSeedMattersForRandomPackingsSeededLatticesAndSeededEffectsOnly) {
  EXPECT_TRUE(seed_matters(cylinder()));  // the seeded FCC lattice: each seed is another cut
  JobSpec aligned = cylinder();
  aligned.sample.lattice = "aligned";
  EXPECT_FALSE(seed_matters(aligned));
  aligned.effects = {{"platen_friction", {{"mu", 0.3}}}};
  EXPECT_FALSE(seed_matters(aligned));
  EXPECT_TRUE(seed_matters(cylinder({{"heterogeneity", {{"weibull_m", 4.0}}}})));
  EXPECT_TRUE(seed_matters(cylinder({{"flaws", {{"fraction", 0.05}}}})));
  EXPECT_TRUE(seed_matters(cylinder({{"packing", {{"radius_ratio", 1.5}}}})));
  JobSpec random = cylinder();
  random.sample.packing = "random";
  EXPECT_TRUE(seed_matters(random));
}

TEST(Effects, HeterogeneityMultipliersHaveMeanOneAndTheWeibullScatter) {
  for (const double m : {4.0, 2.0}) {
    const Stats s = multiplier_stats(m, 1);
    EXPECT_NEAR(s.mean, 1.0, 0.03) << m;
    EXPECT_NEAR(s.cov / weibull_cov(m), 1.0, 0.1) << m << ": CoV " << s.cov;
  }
}

TEST(Effects, HeterogeneityIsAFunctionOfTheSeedAndTheBond) {
  auto strengths = [](std::uint64_t seed) {
    JobSpec job = cylinder({{"heterogeneity", {}}});
    job.sample.seed = seed;
    std::map<BondKey, double> out;
    for (const auto& [key, b] : by_ids(make_specimen(job).bonds)) out[key] = b.fr0;
    return out;
  };
  const auto a = strengths(7), b = strengths(7), c = strengths(8);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(Effects, ScatteredFlawsCutTheRequestedFractionAsBrokenBondsNotBreaks) {
  const std::size_t all = make_specimen(cylinder()).bonds.size();
  const Simulation sim = make_specimen(cylinder({{"flaws", {{"fraction", 0.1}}}}));
  const double cut = static_cast<double>(sim.broken.size()) / static_cast<double>(all);
  EXPECT_NEAR(cut, 0.1, 0.02);
  EXPECT_EQ(sim.bonds.size() + sim.broken.size(), all);
  EXPECT_EQ(broken_pairs(sim), sim.broken.size());  // they meet as broken-bond contacts
  EXPECT_TRUE(sim.breaks.empty());                  // ... but are not breaks of the test
  EXPECT_EQ(sim.broken_total, 0);
  TestResult r;
  count_specimen(sim, r);
  EXPECT_EQ(r.bonds, static_cast<std::int64_t>(sim.bonds.size()));
}

TEST(Effects, CrackFlawsGroupTheCutsOnDiscs) {
  const std::size_t all = make_specimen(cylinder()).bonds.size();
  const Simulation scattered = make_specimen(cylinder({{"flaws", {{"fraction", 0.1}}}}));
  const Simulation cracks =
      make_specimen(cylinder({{"flaws", {{"fraction", 0.1}, {"crack_radius", 3.0}}}}));
  const double cut = static_cast<double>(cracks.broken.size()) / static_cast<double>(all);
  EXPECT_NEAR(cut, 0.1, 0.03);  // a crack cuts some 30 bonds: the count comes in such steps
  EXPECT_EQ(broken_pairs(cracks), cracks.broken.size());
  const double grouped = cut_neighbours(cracks), spread = cut_neighbours(scattered);
  EXPECT_GT(grouped, 3 * spread) << grouped << " vs " << spread;
  // Same seed, same cracks.
  const Simulation again =
      make_specimen(cylinder({{"flaws", {{"fraction", 0.1}, {"crack_radius", 3.0}}}}));
  EXPECT_EQ(by_ids(again.broken).size(), cracks.broken.size());
  for (const auto& [key, b] : by_ids(cracks.broken)) EXPECT_EQ(by_ids(again.broken).count(key), 1u);
}

TEST(Effects, CompressionCouplingDecidesACompressedTwistedBondsFate) {
  // Compressed to half of F_r0 and twisted to 1.49 G_t0: eq. 2 with signed f_r gives 0.99 (holds),
  // with f_r clamped at zero 1.49 (breaks).
  auto survives = [](std::map<std::string, EffectValues> effects) {
    Pair p;
    p.xj.z() -= 0.5 * p.bond.fr0 / p.k.kr_n_m;
    p.qj = rot(1.49 * p.bond.gt0 / p.k.kt_nm_rad, Vec3::UnitZ());
    Simulation sim = pair_sim(p, p.xj, true, std::move(effects));
    sim.particles.orient[1] = p.qj;
    sim.initialise();
    return sim.bonds.size() == 1;
  };
  EXPECT_TRUE(survives({}));
  EXPECT_TRUE(survives({{"compression_coupling", {{"coupling", 1.0}}}}));
  EXPECT_FALSE(survives({{"compression_coupling", {}}}));  // default 0
  EXPECT_EQ(make_specimen(cylinder({{"compression_coupling", {}}})).break_rule.compression_coupling,
            0.0);
}

TEST(Effects, PostBreakFrictionLimitsSlidingOfBrokenPairsOnly) {
  // A pair whose bond broke, pressed together by 0.01 and sliding fast: the tangential force is
  // the Coulomb limit mu F_n.
  auto sliding_force = [](std::map<std::string, EffectValues> effects) {
    const Pair p;
    Simulation sim = pair_sim(p, p.xi + Vec3(0, 0, 1.99), false, std::move(effects));
    sim.particles.vel[1] = Vec3(100, 0, 0);
    EXPECT_DOUBLE_EQ(sim.contact.friction, 0.6);  // never-bonded contacts keep theirs
    sim.initialise();
    return -sim.particles.force[1].x() / (p.k.kr_n_m * 0.01);
  };
  EXPECT_NEAR(sliding_force({}), 0.6, 1e-9);
  EXPECT_NEAR(sliding_force({{"post_break_friction", {}}}), 0.1, 1e-9);
  EXPECT_NEAR(sliding_force({{"post_break_friction", {{"mu", 1.5}}}}), 1.5, 1e-9);
}

TEST(Effects, InteractionRangeBondsTheLatticesSecondNeighboursFromSqrtTwo) {
  // Bonds per particle, and the longest bond over 2R: an FCC lattice has 12 touching neighbours
  // at 2R and 6 more at 2R sqrt(2). Below sqrt(2) nothing changes; from it the second
  // neighbours join, with their own rest length.
  auto bonds_of = [](std::optional<double> factor) {
    JobSpec s = cylinder();
    if (factor) s.effects = {{"interaction_range", {{"factor", *factor}}}};
    const Simulation sim = make_specimen(s);
    std::map<std::int64_t, int> per;
    double longest = 0;
    for (const Bond& b : sim.bonds) {
      ++per[b.id_i];
      ++per[b.id_j];
      longest = std::max(longest, b.r0);
    }
    int most = 0;
    for (const auto& [id, n] : per) most = std::max(most, n);
    return std::tuple{sim.bonds.size(), most, longest / 2.0};
  };
  const auto [plain, plain_most, plain_longest] = bonds_of(std::nullopt);
  EXPECT_EQ(plain_most, 12);
  EXPECT_NEAR(plain_longest, 1.0, 1e-9);
  EXPECT_EQ(std::get<0>(bonds_of(1.0)), plain);
  EXPECT_EQ(std::get<0>(bonds_of(1.4)), plain);
  const auto [wide, wide_most, wide_longest] = bonds_of(1.5);
  EXPECT_EQ(wide_most, 18);
  EXPECT_NEAR(wide_longest, std::sqrt(2.0), 1e-9);
  // Interior particles gain 6 bonds (3 bonds each), surface ones fewer.
  EXPECT_GT(double(wide) / double(plain), 1.3);
  EXPECT_LT(double(wide) / double(plain), 1.5);
  // Where the diagnosis starts exploring the range in this lattice: the least factor it calls a
  // change bonds the very network 1.5 does; in a random packing every factor above 1 adds bonds.
  const EffectParam& factor = find_effect("interaction_range")->params[0];
  ASSERT_NE(factor.first_change_of, nullptr);
  const double first = factor.first_change_of(cylinder());
  EXPECT_GT(first, std::sqrt(2.0));
  EXPECT_LT(first, 1.5);
  EXPECT_EQ(std::get<0>(bonds_of(first)), wide);
  JobSpec random = cylinder();
  random.sample.packing = "random";
  EXPECT_EQ(factor.first_change_of(random), 1.0);
}

TEST(Effects, InteractionRangeSaysWhichFactorsBondTheSameLatticeNetwork) {
  // What a diagnosis's fitted factor stands for: in FCC every factor of a shell [sqrt(n),
  // sqrt(n + 1)) bonds the same network, so 1.45 means "the second neighbours", not 1.45 itself.
  const EffectDef& range = *find_effect("interaction_range");
  auto bonds_at = [](double factor) {
    JobSpec s = cylinder();
    s.effects = {{"interaction_range", {{"factor", factor}}}};
    return make_specimen(s).bonds.size();
  };
  const ValueSpan shell = effect_same_model_span(range, 1.45, cylinder());
  EXPECT_DOUBLE_EQ(shell.from, std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(shell.to, std::sqrt(3.0));
  EXPECT_EQ(bonds_at(shell.from * 1.01), bonds_at(shell.to * 0.99));
  EXPECT_LT(bonds_at(shell.to * 0.99), bonds_at(shell.to * 1.01));
  const ValueSpan touching = effect_same_model_span(range, 1.2, cylinder());
  EXPECT_DOUBLE_EQ(touching.from, 1.0);
  EXPECT_DOUBLE_EQ(touching.to, std::sqrt(2.0));
  // A random packing, and an effect without steps, are their one value.
  JobSpec random = cylinder();
  random.sample.packing = "random";
  const ValueSpan one = effect_same_model_span(range, 1.45, random);
  EXPECT_EQ(one.from, 1.45);
  EXPECT_EQ(one.to, 1.45);
  EXPECT_EQ(effect_same_model_span(*find_effect("rate"), 3.0, cylinder()).to, 3.0);
}

TEST(Effects, InteractionRangeSoftensTheLongerBondsByTheirLengthToTheExponent) {
  // The four stiffnesses of each bond at range 1.5 with stiffness_exponent n against n = 0:
  // touching bonds keep theirs, the second neighbours (at 2R sqrt(2)) get 2^(-n/2) of them.
  auto bonds_of = [](double n) {
    JobSpec s = cylinder();
    s.effects = {{"interaction_range", {{"factor", 1.5}, {"stiffness_exponent", n}}}};
    return make_specimen(s).bonds;
  };
  const std::vector<Bond> stiff = bonds_of(0), soft = bonds_of(3);
  ASSERT_EQ(stiff.size(), soft.size());
  int touching = 0, long_ones = 0;
  for (std::size_t k = 0; k < stiff.size(); ++k) {
    const bool is_long = stiff[k].r0 > 2.0 * (1 + 1e-9);
    const double w = is_long ? std::pow(2.0, -1.5) : 1.0;
    (is_long ? long_ones : touching) += 1;
    EXPECT_NEAR(soft[k].kr, stiff[k].kr * w, 1e-12 * stiff[k].kr) << k;
    EXPECT_NEAR(soft[k].ks, stiff[k].ks * w, 1e-12 * stiff[k].kr) << k;
    EXPECT_NEAR(soft[k].kb, stiff[k].kb * w, 1e-12 * stiff[k].kb) << k;
    EXPECT_NEAR(soft[k].kt, stiff[k].kt * w, 1e-12 * stiff[k].kt) << k;
    EXPECT_EQ(soft[k].fr0, stiff[k].fr0);  // strengths stay the job's
  }
  EXPECT_GT(touching, 0);
  EXPECT_GT(long_ones, 0);
}

TEST(Effects, RollingResistanceResistsRelativeRotationUpToItsLimit) {
  // Two touching particles pressed together by an overlap of 0.01, j spinning about y (the
  // contact normal is z): the rolling moment on j opposes the spin, grows by
  // k_roll = 2.25 k_n mu_r^2 R*^2 per radian of relative rotation, and stops at mu_r R* F_n;
  // i gets the opposite moment. Without the effect there is none.
  auto extra_torque = [](std::map<std::string, EffectValues> effects, int steps) {
    const Pair p;
    Simulation with = pair_sim(p, p.xi + Vec3(0, 0, 1.99), false, std::move(effects));
    Simulation without = pair_sim(p, p.xi + Vec3(0, 0, 1.99), false, {});
    for (Simulation* s : {&with, &without}) {
      s->particles.omega[1] = Vec3(0, 2.0, 0);
      s->initialise();
    }
    for (int k = 1; k < steps; ++k) {
      for (Simulation* s : {&with, &without}) {
        s->particles.torque[0].setZero();
        s->particles.torque[1].setZero();
        s->particles.force[0].setZero();
        s->particles.force[1].setZero();
        accumulate_contact_forces(s->neighbours, s->particles, s->contact, s->dt);
      }
    }
    const Vec3 on_j = with.particles.torque[1] - without.particles.torque[1];
    const Vec3 on_i = with.particles.torque[0] - without.particles.torque[0];
    EXPECT_NEAR((on_i + on_j).norm(), 0.0, 1e-12);
    return on_j;
  };
  const Pair p;
  const double fn = p.k.kr_n_m * 0.01, r_star = 0.5, mu = 0.3;
  const double k_roll = 2.25 * p.k.kr_n_m * mu * mu * r_star * r_star;
  EXPECT_NEAR(extra_torque({}, 1).norm(), 0.0, 1e-12);
  // One step: elastic, 2 rad/s for dt = 1e-3.
  const Vec3 one = extra_torque({{"rolling_resistance", {{"mu_r", mu}}}}, 1);
  EXPECT_NEAR(one.y(), -k_roll * 2.0 * 1e-3, 1e-9 * k_roll);
  EXPECT_NEAR(one.x(), 0.0, 1e-12);
  // Many steps: at the limit.
  const Vec3 many = extra_torque({{"rolling_resistance", {{"mu_r", mu}}}}, 2000);
  EXPECT_NEAR(many.y(), -mu * r_star * fn, 1e-9 * fn);
}

TEST(Effects, RollingHistorySurvivesRebuildsAndTravelsWithMigrants) {
  // A touching pair whose tangential spring is zero but whose rolling spring is not: the history
  // is kept by a rebuild, handed out for a migrating particle, and taken up by another rank's list.
  Particles p;
  p.add(Vec3(0, 0, 0), 1.0, 1.0, 0.4, 5);
  p.add(Vec3(0, 0, 1.99), 1.0, 1.0, 0.4, 9);
  NeighbourList nl;
  nl.skin = 0.5;
  nl.build(p, {}, {});
  ASSERT_EQ(nl.pairs.size(), 1u);
  nl.pairs[0].roll = Vec3(0.1, -0.2, 0);
  nl.build(p, {}, {});
  ASSERT_EQ(nl.pairs.size(), 1u);
  EXPECT_EQ(nl.pairs[0].roll, Vec3(0.1, -0.2, 0));
  std::vector<SpringRecord> leaving;
  nl.history_of(p, 1, leaving);
  ASSERT_EQ(leaving.size(), 1u);
  EXPECT_EQ(leaving[0].id_lo, 5);
  EXPECT_EQ(leaving[0].id_hi, 9);
  EXPECT_EQ(leaving[0].roll, Vec3(0.1, -0.2, 0));
  NeighbourList other;
  other.skin = 0.5;
  other.build(p, {}, {}, leaving);
  ASSERT_EQ(other.pairs.size(), 1u);
  EXPECT_EQ(other.pairs[0].roll, Vec3(0.1, -0.2, 0));
  EXPECT_EQ(other.pairs[0].spring, Vec3::Zero());
}

TEST(Effects, BrazilianFlatsChangeTheDiscsLoadingOnly) {
  JobSpec btt;
  btt.test = TestKind::btt;
  btt.effects = {{"brazilian_flats", {{"angle_deg", 12}}}};
  const JobSpec e = effective_spec(btt);
  EXPECT_EQ(e.loading.btt_geometry, BttGeometry::flattened);
  EXPECT_DOUBLE_EQ(e.loading.flat_angle_deg, 12);
  // From flat platens too; a UCT is left alone.
  btt.loading.btt_geometry = BttGeometry::flat_platens;
  EXPECT_EQ(effective_spec(btt).loading.btt_geometry, BttGeometry::flattened);
  JobSpec uct = btt;
  uct.test = TestKind::uct;
  EXPECT_EQ(effective_spec(uct).loading, [&] {
    JobSpec plain = uct;
    plain.effects.clear();
    return effective_spec(plain).loading;
  }());
  // The walk starts from the job's own flats.
  const EffectDef* flats = find_effect("brazilian_flats");
  ASSERT_NE(flats, nullptr);
  JobSpec narrow;
  narrow.loading.flat_angle_deg = 20;
  EXPECT_DOUBLE_EQ(effect_neutral(flats->params[0], narrow), 20);
  EXPECT_DOUBLE_EQ(effect_value_at(*flats, 1.0, narrow), 10);
  // And the built disc has the flats: narrower flats leave more particles on the disc.
  auto particles = [](double angle) {
    JobSpec s;
    s.test = TestKind::btt;
    s.sample.diameter_m = 20;
    s.sample.thickness_m = 10;
    s.material.kr_n_m = 8000;
    s.effects = {{"brazilian_flats", {{"angle_deg", angle}}}};
    return make_specimen(s).particles.size();
  };
  EXPECT_GT(particles(10), particles(40));
}

TEST(Effects, ConfinementFlagTravelsWithMigrants) {
  Particles p;
  p.add(Vec3(1, 2, 3), 1.0, 1.0, 0.4, 5);
  p.add(Vec3(0, 0, 3), 1.0, 1.0, 0.4, 6);
  EXPECT_EQ(mark_confined(p, 1.5), 1);  // farther than 1.5 from the z axis
  std::vector<double> buf;
  pack_migrant(p, 0, buf);
  pack_migrant(p, 1, buf);
  ASSERT_EQ(buf.size(), 2u * kMigrantDoubles);
  Particles q;
  unpack_migrant(buf.data(), q);
  unpack_migrant(buf.data() + kMigrantDoubles, q);
  EXPECT_EQ(q.id[0], 5);
  EXPECT_EQ(q.confined[0], 1);
  EXPECT_EQ(q.confined[1], 0);
}
