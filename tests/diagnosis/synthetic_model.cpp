#include "synthetic_model.hpp"

#include <cmath>
#include <random>

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

std::vector<double> SyntheticModel::values(const RunRequest& r) const {
  const ModelPoint& p = r.point;
  const double s = effect_on(p) ? p.s : 0.0;
  auto on = [&](const char* name) { return p.effect == name ? s : 0.0; };
  const double lr = std::log(p.fr0_n), ls = std::log(p.fs0_n);
  std::vector<double> out;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const RunConditions& c = targets[i].conditions;
    const double size = std::log(c.diameter_m / kD);
    const double speed = std::log(c.platen_velocity_m_s * r.numerics.speed_factor / kV);
    double ln;
    if (targets[i].observable == Observable::youngs_modulus) {
      ln = std::log(5e3) + 0.01 * ls - 0.2 * on("modulus") - 0.1 * on("size") + 0.1 * on("rate");
    } else {
      // UCT ~ fr0^0.3 fs0^0.7 and BTT ~ fr0^0.8 fs0^0.2 on the base specimen; load ~ D^2.
      const bool disc = c.test == TestKind::btt;
      ln = disc ? std::log(40.0) + 0.8 * lr + 0.2 * ls : std::log(300.0) + 0.3 * lr + 0.7 * ls;
      ln += 2 * size + 0.02 * speed;
      // On the unconfined strength, like a change of the bond strengths; "uniform" is exactly
      // that, so the strengths absorb it.
      ln += -0.6 * on("size") * size + 0.3 * on("rate") * speed - 0.3 * on("uniform");
      if (c.confining_pressure_pa > 0) {
        // The frictional gain of the confined cylinder: a force scale of its own.
        const double area = M_PI * c.diameter_m * c.diameter_m / 4;
        const double ucs = std::exp(ln) / area;
        ln += (1.0 + 2.0 * on("confinement")) * std::log(1 + 3 * c.confining_pressure_pa / ucs);
      }
    }
    ln += 0.01 * std::log(r.numerics.resolution);
    ln += numerical_noise * hash_unit(r, i);
    out.push_back(std::exp(ln));
  }
  return out;
}

std::vector<RunOutcome> SyntheticModel::run_batch(std::span<const RunRequest> requests) {
  std::vector<RunOutcome> out;
  for (const RunRequest& r : requests) {
    RunOutcome o;
    for (double v : values(r)) o.values.push_back(v);
    out.push_back(std::move(o));
    ++runs;
  }
  return out;
}

DiagnosisCampaign twin_campaign(const std::string& effect, double s, double noise,
                                std::uint64_t seed) {
  DiagnosisCampaign c;
  c.name = "synthetic twin: " + (effect.empty() ? std::string("none") : effect);
  c.targets = twin_targets();
  c.candidates = synthetic_candidates();
  c.budget.seeds = {2, 3};
  SyntheticModel truth(c.targets);
  truth.numerical_noise = 0;
  const std::vector<double> v = truth.values({{60.0, 120.0, effect, s}, {1, 1.0, 1.0}});
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;  // a test fixture: library differences do not matter
  for (std::size_t i = 0; i < c.targets.size(); ++i) {
    c.targets[i].value = v[i] * std::exp(noise * normal(rng));
  }
  return c;
}

}  // namespace rockcal::diagnosis::testing
