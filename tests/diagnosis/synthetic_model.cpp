#include "synthetic_model.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "engine/effects/effect.hpp"
#include "engine/spec.hpp"

namespace rockcal::diagnosis::testing {
namespace {

constexpr double kD = 10, kH = 20, kV = 0.05;
// About 0.1 and 0.3 of the base UCS (~370 Pa at the truth), as in the twin design.
constexpr double kP1 = 40, kP2 = 120;

// A deterministic number in [-1, 1] for a run and a target (so replays agree).
double hash_unit(const RunRequest& r, std::size_t target) {
  std::uint64_t h = std::hash<double>{}(r.point.fr0_n) * 31 + std::hash<double>{}(r.point.fs0_n);
  h = h * 131 + std::hash<double>{}(r.point.s) + r.numerics.seed * 1000003 + target * 7919;
  h ^= h >> 29;
  h *= 0xbf58476d1ce4e5b9ULL;
  h ^= h >> 32;
  return double(h % 2000001) / 1e6 - 1.0;
}

Target target(std::string id, TestKind test, Observable o, Role role, double d, double p,
              double v) {
  Target t;
  t.id = std::move(id);
  t.observable = o;
  t.role = role;
  t.conditions = {test, d, 2 * d, d / 2, p, v};
  t.sigma = 0.02;
  return t;
}

// Which measured observation's mark a run under these conditions carries (measured_marks is keyed
// by the real twin design's ids): the design's own tests are their ids; a test the design does not
// have takes the mark of the one that fails the same way, or none.
std::string mark_of(const Target& t) {
  const RunConditions& c = t.conditions;
  switch (c.test) {
    case TestKind::triaxial:
      // Measured at 0.1 and 0.3 of the UCS: a confinement carries the nearer one's.
      return c.confining_pressure_pa < 0.5 * (kP1 + kP2) ? "tri-low" : "tri-high";
    case TestKind::btt:
      // A larger disc was measured, and a faster one; a thinner or thicker one of the design's
      // diameter splits like it (the disc's stress field is plane), so the re-fit absorbs whatever
      // it moves.
      if (c.platen_velocity_m_s > kV) return "btt-fast";
      return c.diameter_m > kD ? "btt-large" : "";
    default:
      break;
  }
  if (t.observable == Observable::youngs_modulus) return "uct-modulus";
  if (t.observable == Observable::peak_strain) return "uct-peak-strain";
  if (c.platen_velocity_m_s > kV) return "uct-fast";
  // The platens' end zones hold the whole of a squat (H/D = 1) cylinder, where the effects that
  // change how bonds fail under compression show; a slender one fails by a band between them as the
  // H/D 2 cylinder does, whose peak the re-fitted strengths absorb.
  return c.height_m <= 1.25 * c.diameter_m ? "uct-squat" : "";
}

}  // namespace

std::vector<Target> twin_targets() {
  using enum Observable;
  using enum Role;
  return {target("uct-peak", TestKind::uct, peak_load, calibration, kD, 0, kV),
          target("uct-modulus", TestKind::uct, youngs_modulus, calibration, kD, 0, kV),
          target("btt-peak", TestKind::btt, peak_load, calibration, kD, 0, kV),
          target("tri-low", TestKind::triaxial, peak_load, calibration, kD, kP1, kV),
          target("tri-high", TestKind::triaxial, peak_load, held_out, kD, kP2, kV),
          target("uct-large", TestKind::uct, peak_load, held_out, 1.5 * kD, 0, kV),
          target("btt-large", TestKind::btt, peak_load, held_out, 1.5 * kD, 0, kV),
          target("uct-fast", TestKind::uct, peak_load, held_out, kD, 0, 4 * kV)};
}

std::vector<Candidate> synthetic_candidates() {
  std::vector<Candidate> out;
  for (const char* name : {"size", "confinement", "rate", "uniform", "modulus"}) {
    out.push_back({name, "s", "", [](double s) { return s; }});
  }
  return out;
}

Marks measured_marks() {
  // bench/effects/signatures.py --slow-factor 0.25 (docs/effects.md, "Signatures"): the twin
  // design's two-rate loading, D/R 20, 3 seeds, base (64, 128) N, each effect at its strong value,
  // one Newton step of the strengths; the cells at 2 standard errors of the seeds' scatter or more
  // that also exceed the step's own uncertainty (the re-fit follows the discs' scatter: 0.5 in ln
  // on the UCT's modulus). The rate columns are the changes of d ln UCS and d ln BTS / d ln speed:
  // at the design's 4x speed, x ln 4.
  const double ln4 = std::log(4.0);
  return {
      // The one-step re-fit misses a random packing's UCS by -2.5 in ln on this loading, so its
      // cells would be that miss: the fixed-speed table's row (a -0.5 miss) stands in.
      {"packing",
       {{"uct-modulus", -1.171},
        {"tri-low", -0.915},
        {"tri-high", -1.143},
        {"uct-fast", 0.147 * ln4},
        {"uct-peak-strain", 0.733}}},
      // The slow late phase takes most of the inertial gain: only the fast tests still show it.
      {"rate", {{"uct-fast", 0.144 * ln4}, {"btt-fast", 0.253 * ln4}}},
      {"compression_coupling",
       {{"uct-squat", -0.646},
        {"tri-low", -0.871},
        {"tri-high", -0.621},
        {"uct-peak-strain", -0.628}}},
      {"interaction_range",
       {{"uct-squat", 0.163},
        {"uct-modulus", 1.009},
        {"tri-low", 0.321},
        {"tri-high", 0.499},
        {"btt-fast", 0.119 * ln4},
        {"uct-peak-strain", -0.690}}},
      // Inside the step's uncertainty (heterogeneity 2, flaws 0.15: the UCT's modulus +0.14 and
      // +0.15, as the flats', which cannot change a UCT: the re-fit's scatter), below 2 standard
      // errors everywhere (post-break friction 0.05, rolling resistance 0.3), or not measured
      // with the strengths re-fitted (platen friction 0.5 hardened to the strain limit without a
      // peak).
      {"heterogeneity", {}},
      {"flaws", {}},
      {"post_break_friction", {}},
      {"rolling_resistance", {}},
      {"brazilian_flats", {}},
      {"platen_friction", {}},
  };
}

double first_change_s(const std::string& effect) {
  const EffectDef* def = find_effect(effect);
  return def ? effect_first_change_fraction(*def, JobSpec{}) : 0.0;
}

double hidden_s(const std::string& effect, double s) {
  return std::max(s, first_change_s(effect));
}

double mark_share(const std::string& effect, double s) {
  const double first = first_change_s(effect);
  if (first <= 0.0) return s;
  return s >= first - 1e-12 ? 1.0 : 0.0;
}

std::vector<double> SyntheticModel::values(const RunRequest& r) const {
  return values(r, targets);
}

std::vector<double> SyntheticModel::values(const RunRequest& r,
                                           const std::vector<Target>& at) const {
  const ModelPoint& p = r.point;
  const double s = effect_on(p) ? p.s : 0.0;
  const auto measured = marks.find(p.effect);
  // The formula candidates' own terms; an effect with measured marks (the registry's rate shares
  // the formula "rate"'s name) moves only what it was measured to move.
  auto on = [&](const char* name) { return p.effect == name && measured == marks.end() ? s : 0.0; };
  const double lr = std::log(p.fr0_n), ls = std::log(p.fs0_n);
  // ln(peak load) of a run under conditions c.
  auto peak = [&](const RunConditions& c) {
    const double size = std::log(c.diameter_m / kD);
    const double speed = std::log(c.platen_velocity_m_s * r.numerics.speed_factor / kV);
    // UCT ~ fr0^0.3 fs0^0.7 and BTT ~ fr0^0.8 fs0^0.2 on the base specimen; load ~ D^2.
    const bool disc = c.test == TestKind::btt;
    double ln = disc ? std::log(40.0) + 0.8 * lr + 0.2 * ls : std::log(300.0) + 0.3 * lr + 0.7 * ls;
    ln += 2 * size + 0.02 * speed;
    // A disc's load grows with its thickness (BTS = 2P / (pi D t)): t = D / 2 is the base disc.
    if (disc) ln += std::log(2 * c.thickness_m / c.diameter_m);
    // On the unconfined strength, like a change of the bond strengths; "uniform" is exactly
    // that, so the strengths absorb it.
    ln += -0.6 * on("size") * size + 0.3 * on("rate") * speed - 0.3 * on("uniform");
    // "fading": a mark on the confined peaks that shows only where F_s0 is not well above F_r0,
    // 1 / (1 + (F_s0 / 1.3 F_r0)^8) of it: 3% at the truth's F_s0 = 2 F_r0, 89% at equal
    // strengths (as the compression coupling, which weighs a bond's compression by 1 / F_r0,
    // fades where F_r0 is well above F_s0).
    if (c.confining_pressure_pa > 0) {
      ln -= 0.3 * on("fading") / (1 + std::pow(p.fs0_n / (1.3 * p.fr0_n), 8));
    }
    if (c.confining_pressure_pa > 0) {
      // The frictional gain of the confined cylinder: a force scale of its own.
      const double area = M_PI * c.diameter_m * c.diameter_m / 4;
      const double ucs = std::exp(ln) / area;
      ln += (1.0 + 2.0 * on("confinement")) * std::log(1 + 3 * c.confining_pressure_pa / ucs);
    }
    return ln;
  };
  const double modulus =
      std::log(5e3) + 0.01 * ls - 0.2 * on("modulus") - 0.1 * on("size") + 0.1 * on("rate");
  std::vector<double> out;
  for (std::size_t i = 0; i < at.size(); ++i) {
    const RunConditions& c = at[i].conditions;
    double ln;
    switch (at[i].observable) {
      case Observable::youngs_modulus:
        ln = modulus;
        break;
      case Observable::peak_strain:  // about 1.5 x UCS / E: the curve bends before the peak
        ln = std::log(1.5) + peak(c) - std::log(M_PI * c.diameter_m * c.diameter_m / 4) - modulus;
        break;
      default:
        ln = peak(c);
    }
    if (measured != marks.end()) {
      const auto mark = measured->second.find(mark_of(at[i]));
      if (mark != measured->second.end()) ln += mark_share(p.effect, s) * mark->second;
    }
    ln += 0.01 * std::log(r.numerics.resolution);
    ln += numerical_noise * hash_unit(r, i);
    out.push_back(std::exp(ln));
  }
  return out;
}

std::vector<RunOutcome> SyntheticModel::run_batch(std::span<const RunRequest> requests) {
  return run_on(requests, targets);
}

std::vector<RunOutcome> SyntheticModel::run_on(std::span<const RunRequest> requests,
                                               const std::vector<Target>& on) {
  std::vector<RunOutcome> out;
  for (const RunRequest& r : requests) {
    RunOutcome o;
    for (double v : values(r, on)) o.values.push_back(v);
    out.push_back(std::move(o));
    ++runs;
  }
  return out;
}

namespace {

// Lab values: the noise-free model at the truth (60, 120) with the hidden effect, times
// exp(noise x N(0,1)).
void draw_lab_values(DiagnosisCampaign& c, const Marks& marks, const std::string& effect, double s,
                     double noise, std::uint64_t seed) {
  SyntheticModel truth(c.targets);
  truth.numerical_noise = 0;
  truth.marks = marks;
  const std::vector<double> v = truth.values({{60.0, 120.0, effect, s}, {1, 1.0, 1.0}});
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;  // a test fixture: library differences do not matter
  for (std::size_t i = 0; i < c.targets.size(); ++i) {
    c.targets[i].value = v[i] * std::exp(noise * normal(rng));
  }
}

}  // namespace

DiagnosisCampaign twin_campaign(const std::string& effect, double s, double noise,
                                std::uint64_t seed) {
  DiagnosisCampaign c;
  c.name = "synthetic twin: " + (effect.empty() ? std::string("none") : effect);
  c.targets = twin_targets();
  c.candidates = synthetic_candidates();
  c.budget.seeds = {2, 3};
  draw_lab_values(c, {}, effect, s, noise, seed);
  return c;
}

DiagnosisCampaign registry_twin_campaign(const std::string& effect, double s, double noise,
                                         std::uint64_t seed) {
  DiagnosisCampaign c;
  c.name = "measured-mark twin: " + (effect.empty() ? std::string("none") : effect);
  // The real twin design's observations (twin_design.hpp): the UCT at H/D = 1 instead of the
  // formula design's 1.5x cylinder, the fast disc and the peak strain.
  c.targets = twin_targets();
  for (Target& t : c.targets) {
    if (t.id != "uct-large") continue;
    t = target("uct-squat", TestKind::uct, Observable::peak_load, Role::held_out, kD, 0, kV);
    t.conditions.height_m = kD;
  }
  c.targets.push_back(
      target("btt-fast", TestKind::btt, Observable::peak_load, Role::calibration, kD, 0, 4 * kV));
  c.targets.push_back(
      target("uct-peak-strain", TestKind::uct, Observable::peak_strain, Role::held_out, kD, 0, kV));
  c.candidates = registry_candidates(JobSpec{});
  c.budget.seeds = {2, 3};
  draw_lab_values(c, measured_marks(), effect, hidden_s(effect, s), noise, seed);
  return c;
}

}  // namespace rockcal::diagnosis::testing
