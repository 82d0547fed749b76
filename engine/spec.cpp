#include "engine/spec.hpp"

#include "engine/loadtests/loading_speed.hpp"

#include <cmath>
#include <cstdio>
#include <set>

#include "engine/run_cost.hpp"
#include "engine/units.hpp"

namespace rockcal {
namespace {

using nlohmann::json;

// Physical values span many orders of magnitude between SI lab units (a grain of 1e-4 m, kr of
// 1e8 N/m, 2700 kg/m^3) and the model units of eq. 4 (radius 1, kr 8000, density 1); these bounds
// lie orders of magnitude beyond both, so that only absurd values (1e-300, 1e20 N/m) are refused
// here. What the values give together (time steps, the platen against the wave speed) is checked
// after parsing.
struct Magnitudes {
  double lo, hi;
  const char* unit;
};
constexpr Magnitudes kDensityRange{1e-6, 1e6, "kg/m^3"};
constexpr Magnitudes kStiffnessRange{1e-6, 1e13, "N/m"};
constexpr Magnitudes kModulusRange{1e-6, 1e13, "Pa"};
constexpr Magnitudes kSpeedRange{1e-9, 1e3, "m/s"};
constexpr Magnitudes kTimeStepRange{1e-15, 1e3, "s"};
// A platen faster than this fraction of the specimen's compression-wave speed strikes it: an
// impact, not a quasi-static test (the seed case runs at 5e-4 of it).
constexpr double kMaxPlatenWaveFraction = 0.1;

// Three significant digits: "95.7", "1e-06", "1e+13".
std::string three_digits(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

// Reads one JSON object, remembering which keys were consumed so unknown keys can be reported.
class ObjectReader {
 public:
  ObjectReader(const json& obj, std::string path) : obj_(obj), path_(std::move(path)) {
    if (!obj_.is_object())
      throw SpecError(path_.empty() ? "(root)" : path_, "must be a JSON object");
  }

  std::string field(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }

  const json* find(const std::string& key) {
    seen_.insert(key);
    auto it = obj_.find(key);
    return it == obj_.end() ? nullptr : &*it;
  }

  // A finite number; `dt`-like fields that also accept strings are handled by the caller.
  std::optional<double> number(const std::string& key) {
    const json* v = find(key);
    if (!v) return std::nullopt;
    if (!v->is_number()) throw SpecError(field(key), "must be a number");
    double x = v->get<double>();
    if (!std::isfinite(x)) throw SpecError(field(key), "must be finite");
    return x;
  }

  double positive(const std::string& key, double fallback) {
    double x = number(key).value_or(fallback);
    if (!(x > 0)) throw SpecError(field(key), "must be positive");
    return x;
  }

  // A positive physical value within `range` (see Magnitudes).
  double magnitude(const std::string& key, double fallback, const Magnitudes& range) {
    double x = positive(key, fallback);
    if (x < range.lo || x > range.hi) {
      throw SpecError(field(key), "must be in [" + three_digits(range.lo) + ", " +
                                      three_digits(range.hi) + "] " + range.unit + "; " +
                                      three_digits(x) + " is absurd in SI and in model units");
    }
    return x;
  }

  double in_range(const std::string& key, double fallback, double lo, double hi, bool hi_open) {
    double x = number(key).value_or(fallback);
    if (x < lo || x > hi || (hi_open && x == hi)) {
      throw SpecError(field(key),
                      "must be in [" + fmt(lo) + ", " + fmt(hi) + (hi_open ? ")" : "]"));
    }
    return x;
  }

  std::optional<std::int64_t> integer(const std::string& key, std::int64_t lo, std::int64_t hi) {
    const json* v = find(key);
    if (!v) return std::nullopt;
    if (!v->is_number_integer() && !v->is_number_unsigned()) {
      throw SpecError(field(key), "must be an integer");
    }
    if (v->is_number_unsigned() && v->get<std::uint64_t>() > static_cast<std::uint64_t>(hi)) {
      throw SpecError(field(key), "must be at most " + std::to_string(hi));
    }
    std::int64_t x = v->get<std::int64_t>();
    if (x < lo || x > hi) {
      throw SpecError(field(key),
                      "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    }
    return x;
  }

  std::optional<bool> boolean(const std::string& key) {
    const json* v = find(key);
    if (!v) return std::nullopt;
    if (!v->is_boolean()) throw SpecError(field(key), "must be true or false");
    return v->get<bool>();
  }

  std::optional<std::string> string(const std::string& key) {
    const json* v = find(key);
    if (!v) return std::nullopt;
    if (!v->is_string()) throw SpecError(field(key), "must be a string");
    return v->get<std::string>();
  }

  void reject_unknown() const {
    for (auto it = obj_.begin(); it != obj_.end(); ++it) {
      if (!seen_.count(it.key())) throw SpecError(field(it.key()), "unknown field");
    }
  }

  static std::string fmt(double x) {
    json j = x;
    return j.dump();
  }

 private:
  const json& obj_;
  std::string path_;
  std::set<std::string> seen_;
};

// A count for a message: whole up to a billion, then three significant digits ("1.39e+23").
std::string count_text(double x) {
  return x < 1e9 ? std::to_string(std::llround(x)) : three_digits(x);
}

// Particles in the larger of the UCT cylinder and the BTT disc at the FCC density. Computed from
// the ratios to the radius (each at least 2, so never 0 x inf): huge sizes give +inf, never NaN.
double particle_estimate(const SampleSpec& s) {
  const double fcc_cell_share = 4.0 * std::sqrt(2.0);  // volume per particle / R^3
  const double d = s.diameter_m / s.radius_m;
  const double l = std::max(s.height_m, s.btt_thickness()) / s.radius_m;
  return M_PI * 0.25 / fcc_cell_share * d * d * l;
}

SampleSpec parse_sample(ObjectReader& root) {
  SampleSpec s;
  const json* v = root.find("sample");
  if (!v) return s;
  ObjectReader r(*v, "sample");
  s.diameter_m = r.positive("diameter", s.diameter_m);
  s.height_m = r.positive("height", s.height_m);
  if (auto t = r.number("thickness")) {
    if (!(*t > 0)) throw SpecError("sample.thickness", "must be positive");
    s.thickness_m = *t;
  }
  s.packing = r.string("packing").value_or(s.packing);
  if (s.packing != "fcc" && s.packing != "random")
    throw SpecError("sample.packing", "unknown packing '" + s.packing + "' (known: fcc, random)");
  if (s.packing == "random") s.radius_ratio = 1.5;
  s.radius_ratio = r.in_range("radius_ratio", s.radius_ratio, 1.0, 5.0, false);
  if (s.packing == "fcc" && s.radius_ratio != 1.0)
    throw SpecError("sample.radius_ratio", "applies to random packings only (FCC is monodisperse)");
  s.radius_m = r.positive("radius", s.radius_m);
  if (auto seed = r.integer("seed", 0, std::numeric_limits<std::int64_t>::max())) s.seed = *seed;
  if (auto lattice = r.string("lattice")) {
    if (s.packing != "fcc") throw SpecError("sample.lattice", "applies to FCC packings only");
    if (*lattice != "seeded" && *lattice != "aligned")
      throw SpecError("sample.lattice",
                      "unknown lattice placement '" + *lattice + "' (known: seeded, aligned)");
    s.lattice = *lattice;
  }
  r.reject_unknown();

  // Sizes relative to the particle: a specimen must hold a few particles across, and not billions.
  const double cells = 2.0 * s.radius_m;
  if (s.diameter_m < 2.0 * cells)
    throw SpecError("sample.diameter", "must be at least 4 particle radii");
  if (s.height_m < 2.0 * cells)
    throw SpecError("sample.height", "must be at least 4 particle radii");
  if (s.btt_thickness() < cells)
    throw SpecError("sample.thickness", "must be at least 2 particle radii");
  const double estimate = particle_estimate(s);
  if (!(estimate <= kMaxParticles)) {  // also refuses an estimate that is not a number
    const std::string about =
        std::isfinite(estimate) ? "about " + count_text(estimate) : "an unbounded number of";
    throw SpecError("sample.diameter", "specimen would hold " + about + " particles (limit " +
                                           count_text(kMaxParticles) + ")");
  }
  return s;
}

MaterialSpec parse_material(ObjectReader& root) {
  MaterialSpec m;
  const json* v = root.find("material");
  if (!v) throw SpecError("material", "is required");
  ObjectReader r(*v, "material");
  m.density_kg_m3 = r.magnitude("density", m.density_kg_m3, kDensityRange);
  if (r.number("kr")) m.kr_n_m = r.magnitude("kr", 1.0, kStiffnessRange);
  if (r.number("youngs_modulus"))
    m.youngs_modulus_pa = r.magnitude("youngs_modulus", 1.0, kModulusRange);
  if (m.kr_n_m && m.youngs_modulus_pa) {
    throw SpecError("material.youngs_modulus", "give either kr or youngs_modulus, not both");
  }
  if (!m.kr_n_m && !m.youngs_modulus_pa)
    throw SpecError("material.kr", "kr or youngs_modulus is required");
  // Eq. 3 gives positive K_s, K_b, K_t only for -1 < nu < 1/3 (and K_r needs nu < 1/2).
  m.nu = r.number("nu").value_or(m.nu);
  if (!(m.nu > -1.0 && m.nu < 1.0 / 3.0)) {
    throw SpecError("material.nu",
                    "must be in (-1, 1/3): eq. 3 gives non-positive shear stiffness otherwise");
  }
  r.reject_unknown();
  return m;
}

BondSpec parse_bond(ObjectReader& root, const std::optional<BondSpec>& given) {
  BondSpec b;
  const json* v = root.find("bond");
  if (given) {
    // The caller sets the strengths; a block the template has may name them only.
    if (v) {
      ObjectReader r(*v, "bond");
      r.find("fr0");
      r.find("fs0");
      r.reject_unknown();
    }
    if (!(given->fr0_n > 0) || !std::isfinite(given->fr0_n))
      throw SpecError("bond.fr0", "must be positive and finite");
    if (!(given->fs0_n > 0) || !std::isfinite(given->fs0_n))
      throw SpecError("bond.fs0", "must be positive and finite");
    return *given;
  }
  if (!v) throw SpecError("bond", "is required");
  ObjectReader r(*v, "bond");
  if (!r.find("fr0")) throw SpecError("bond.fr0", "is required");
  if (!r.find("fs0")) throw SpecError("bond.fs0", "is required");
  b.fr0_n = r.positive("fr0", b.fr0_n);
  b.fs0_n = r.positive("fs0", b.fs0_n);
  r.reject_unknown();
  return b;
}

ContactSpec parse_contact(ObjectReader& root) {
  ContactSpec c;
  const json* v = root.find("contact");
  if (!v) return c;
  ObjectReader r(*v, "contact");
  c.friction = r.in_range("friction", c.friction, 0.0, 10.0, false);
  r.reject_unknown();
  return c;
}

// The Brazilian set-up: the geometry and the one parameter that belongs to it.
void parse_btt_geometry(ObjectReader& r, TestKind test, LoadingSpec& l) {
  const bool btt = test == TestKind::btt;
  if (auto name = r.string("btt_geometry")) {
    if (!btt) throw SpecError("loading.btt_geometry", "applies to the btt test only");
    auto g = btt_geometry_from_string(*name);
    if (!g)
      throw SpecError(
          "loading.btt_geometry",
          "unknown geometry '" + *name + "' (known: curved_jaws, flattened, flat_platens)");
    l.btt_geometry = *g;
  }
  if (r.number("jaw_radius_ratio")) {
    if (!btt || l.btt_geometry != BttGeometry::curved_jaws)
      throw SpecError("loading.jaw_radius_ratio", "applies to btt_geometry curved_jaws only");
    // Below ~1.1 the jaw wraps the disc; above ~3 it is a flat platen with a bump.
    l.jaw_radius_ratio = r.in_range("jaw_radius_ratio", l.jaw_radius_ratio, 1.1, 3.0, false);
  }
  if (r.number("flat_angle_deg")) {
    if (!btt || l.btt_geometry != BttGeometry::flattened)
      throw SpecError("loading.flat_angle_deg", "applies to btt_geometry flattened only");
    // Wang et al. (2004) analyse 2 alpha up to 30 degrees; beyond 60 the disc is a block.
    l.flat_angle_deg = r.in_range("flat_angle_deg", l.flat_angle_deg, 5.0, 60.0, false);
  }
}

LoadingSpec parse_loading(ObjectReader& root, TestKind test) {
  LoadingSpec l;
  const json* v = root.find("loading");
  if (!v) return l;
  ObjectReader r(*v, "loading");
  if (const json* v = r.find("platen_velocity")) {
    if (v->is_string()) {
      if (v->get<std::string>() != "auto")
        throw SpecError("loading.platen_velocity", "must be \"auto\" or a positive number");
      l.platen_velocity_m_s.reset();
    } else {
      l.platen_velocity_m_s =
          r.magnitude("platen_velocity", l.platen_velocity_m_s.value_or(0.05), kSpeedRange);
    }
  }
  if (r.number("auto_transits")) {
    if (l.platen_velocity_m_s)
      throw SpecError("loading.auto_transits", "applies to platen_velocity \"auto\" only");
    l.auto_transits = r.in_range("auto_transits", l.auto_transits, 1.0, 1000.0, false);
  }
  if (const json* w = r.find("past_window")) {
    if (l.platen_velocity_m_s)
      throw SpecError("loading.past_window", "applies to platen_velocity \"auto\" only");
    const std::string mode = w->is_string() ? w->get<std::string>() : "";
    if (mode != "stop" && mode != "speed_up")
      throw SpecError("loading.past_window", "must be \"stop\" or \"speed_up\"");
    l.speed_up_past_window = mode == "speed_up";
  }
  if (const std::optional<bool> rerun = r.boolean("quasi_static_rerun")) {
    if (l.platen_velocity_m_s)
      throw SpecError("loading.quasi_static_rerun", "applies to platen_velocity \"auto\" only");
    l.quasi_static_rerun = *rerun;  // the elastic test, loaded at its own pace, ignores it
  }
  if (r.number("follow_transits")) {
    if (l.platen_velocity_m_s)
      throw SpecError("loading.follow_transits", "applies to platen_velocity \"auto\" only");
    l.follow_transits = r.in_range("follow_transits", l.follow_transits, 10.0, 10000.0, false);
  }
  if (const json* dt = r.find("dt")) {
    if (dt->is_string()) {
      if (dt->get<std::string>() != "auto")
        throw SpecError("loading.dt", "must be \"auto\" or a positive number");
    } else {
      l.dt_s = r.magnitude("dt", 1.0, kTimeStepRange);
    }
  }
  l.dt_safety = r.in_range("dt_safety", l.dt_safety, 0.01, 1.0, false);
  l.ramp_fraction = r.in_range("ramp_fraction", l.ramp_fraction, 0.0, 1.0, false);
  l.stop_load_fraction = r.in_range("stop_load_fraction", l.stop_load_fraction, 0.0, 1.0, true);
  // A Brazilian disc closes by several percent of D before it splits (the contacts flatten): it
  // gets twice the compression tests' strain by default.
  if (test == TestKind::btt) l.max_strain = kBttMaxStrain;
  l.max_strain = r.in_range("max_strain", l.max_strain, 1e-9, 0.9, false);
  l.max_steps = r.integer("max_steps", 1, kMaxSteps);
  l.platen_friction = r.in_range("platen_friction", l.platen_friction, 0.0, 10.0, false);
  if (const json* seat = r.find("seating_load")) {
    if (test == TestKind::elastic)
      throw SpecError("loading.seating_load", "applies to the uct, btt and triaxial tests");
    if (seat->is_string()) {
      if (seat->get<std::string>() != "auto")
        throw SpecError("loading.seating_load", "must be \"auto\" or a positive number");
    } else {
      l.seating_load_n = r.positive("seating_load", 1.0);
    }
  }
  parse_btt_geometry(r, test, l);
  if (auto p = r.number("confining_pressure")) {
    if (test != TestKind::triaxial)
      throw SpecError("loading.confining_pressure", "applies to the triaxial test only");
    if (*p < 0) throw SpecError("loading.confining_pressure", "must be non-negative");
    l.confining_pressure_pa = *p;
  }
  l.elastic_strain = r.in_range("elastic_strain", l.elastic_strain, 1e-9, 0.01, false);
  l.slow_factor = r.in_range("slow_factor", l.slow_factor, 1e-4, 1.0, false);
  l.slow_trigger_broken_fraction =
      r.in_range("slow_trigger_broken_fraction", l.slow_trigger_broken_fraction, 0.0, 1.0, false);
  l.rate_study = r.boolean("rate_study").value_or(l.rate_study);
  l.rate_study_runs = r.integer("rate_study_runs", 3, 6).value_or(l.rate_study_runs);
  if (l.rate_study && l.quasi_static_rerun)
    throw SpecError("loading.quasi_static_rerun",
                    "not with loading.rate_study (the study runs slower on its own)");
  r.reject_unknown();
  return l;
}

DampingSpec parse_damping(ObjectReader& root) {
  DampingSpec d;
  const json* v = root.find("damping");
  if (!v) return d;
  ObjectReader r(*v, "damping");
  d.local = r.in_range("local", d.local, 0.0, 1.0, true);
  d.viscous = r.in_range("viscous", d.viscous, 0.0, 1e12, false);
  r.reject_unknown();
  return d;
}

// "effects": {"NAME": {"PARAM": value, ...}, ...}. Names and types here; defaults and ranges in
// complete_effects(), which also checks specs built in code.
std::map<std::string, EffectValues> parse_effects(ObjectReader& root) {
  std::map<std::string, EffectValues> effects;
  const json* v = root.find("effects");
  if (!v) return effects;
  if (!v->is_object()) throw SpecError("effects", "must be a JSON object");
  for (auto it = v->begin(); it != v->end(); ++it) {
    const std::string field = "effects." + it.key();
    const EffectDef* def = find_effect(it.key());
    if (!def) throw SpecError(field, "unknown effect (known: " + known_effect_names() + ")");
    ObjectReader r(it.value(), field);
    EffectValues& values = effects[it.key()];
    for (const EffectParam& p : def->params)
      if (auto x = r.number(p.name)) values[p.name] = *x;
    r.reject_unknown();
  }
  complete_effects(effects);
  return effects;
}

OutputSpec parse_output(ObjectReader& root, const SampleSpec& sample) {
  OutputSpec o;
  const json* v = root.find("output");
  if (!v) return o;
  ObjectReader r(*v, "output");
  o.vtk = r.boolean("vtk").value_or(o.vtk);
  o.vtk_frames = r.integer("vtk_frames", 1, kMaxVtkFrames).value_or(o.vtk_frames);
  o.curve_points = r.integer("curve_points", 10, kMaxCurvePoints).value_or(o.curve_points);
  o.progress_seconds = r.in_range("progress_seconds", o.progress_seconds, 0.0, 86400.0, false);
  r.reject_unknown();
  const double particle_frames = double(o.vtk_frames) * particle_estimate(sample);
  if (o.vtk && !(particle_frames <= kMaxVtkParticleFrames)) {
    throw SpecError("output.vtk_frames",
                    "frames x particles is about " + count_text(particle_frames) + " (limit " +
                        count_text(kMaxVtkParticleFrames) + "): fewer frames, or a coarser sample");
  }
  return o;
}

// The run's length, bounded before it starts: the platen well below the wave speed, and at most
// kMaxSteps time steps in all (run_cost.hpp).
void check_cost(const JobSpec& run) {
  const double c = wave_speed(run);
  const double v = platen_speed(run);
  if (run.test != TestKind::elastic && !(v <= kMaxPlatenWaveFraction * c)) {
    throw SpecError("loading.platen_velocity",
                    ObjectReader::fmt(v) + " m/s is over " +
                        ObjectReader::fmt(kMaxPlatenWaveFraction) +
                        " of the specimen's wave speed (" + three_digits(c) +
                        " m/s from material and sample): an impact, not a quasi-static test");
  }
  const double steps = estimated_steps(run);
  if (steps <= static_cast<double>(kMaxSteps)) return;
  const std::string about =
      std::isfinite(steps) ? "about " + count_text(steps) : "an unbounded number of";
  const std::string limit = " (limit " + count_text(static_cast<double>(kMaxSteps)) + ")";
  // Name what made it long: a given step finer than the automatic one, a rate study's slower runs,
  // two-rate loading's slow phase, or else the platen speed against the material's wave speed.
  JobSpec alternative = run;
  alternative.loading.dt_s.reset();
  if (run.loading.dt_s && estimated_steps(alternative) <= kMaxSteps)
    throw SpecError("loading.dt", "of " + ObjectReader::fmt(*run.loading.dt_s) +
                                      " s gives the job " + about + " time steps" + limit);
  alternative = run;
  alternative.loading.rate_study = false;
  if (run.loading.rate_study && estimated_steps(alternative) <= kMaxSteps)
    throw SpecError("loading.rate_study_runs",
                    "gives the job " + about + " time steps in all its runs" + limit);
  alternative.loading.slow_factor = 1.0;
  if (run.loading.slow_factor < 1.0 && estimated_steps(alternative) <= kMaxSteps)
    throw SpecError("loading.slow_factor", "gives the job " + about + " time steps" + limit);
  throw SpecError("loading.platen_velocity",
                  ObjectReader::fmt(v) + " m/s against a wave speed of " + three_digits(c) +
                      " m/s gives the job " + about + " time steps" + limit);
}

JobSpec parse_body(ObjectReader& r, TestKind test, const std::optional<BondSpec>& bond = {}) {
  JobSpec s;
  s.test = test;
  s.sample = parse_sample(r);
  s.material = parse_material(r);
  s.bond = parse_bond(r, bond);
  s.contact = parse_contact(r);
  s.loading = parse_loading(r, test);
  s.damping = parse_damping(r);
  s.output = parse_output(r, s.sample);
  s.effects = parse_effects(r);
  r.reject_unknown();
  // The checks that follow look at the spec a run will use: with the effects' changes.
  const JobSpec run = effective_spec(s);
  const double limit = critical_time_step(run);
  if (!(limit > 0.0) || !std::isfinite(limit)) {
    // Extreme density, stiffness or radius (overflow or underflow): no step could be taken.
    throw SpecError("material",
                    "density, stiffness and particle radius give a critical time step of " +
                        three_digits(limit) + " s: no usable step");
  }
  if (run.loading.dt_s) {
    // An explicit step above the stability limit would blow up silently; refuse it up front.
    if (!(*run.loading.dt_s <= limit)) {
      throw SpecError("loading.dt",
                      "exceeds the stability limit " + ObjectReader::fmt(limit) + " s");
    }
  }
  check_cost(run);
  return s;
}

}  // namespace

const char* to_string(TestKind test) {
  switch (test) {
    case TestKind::uct:
      return "uct";
    case TestKind::btt:
      return "btt";
    case TestKind::elastic:
      return "elastic";
    case TestKind::triaxial:
      return "triaxial";
  }
  return "?";
}

const char* to_string(BttGeometry geometry) {
  switch (geometry) {
    case BttGeometry::flat_platens:
      return "flat_platens";
    case BttGeometry::curved_jaws:
      return "curved_jaws";
    case BttGeometry::flattened:
      return "flattened";
  }
  return "?";
}

std::optional<BttGeometry> btt_geometry_from_string(const std::string& name) {
  for (BttGeometry g :
       {BttGeometry::flat_platens, BttGeometry::curved_jaws, BttGeometry::flattened})
    if (name == to_string(g)) return g;
  return std::nullopt;
}

std::optional<TestKind> test_kind_from_string(const std::string& name) {
  if (name == "uct") return TestKind::uct;
  if (name == "btt") return TestKind::btt;
  if (name == "elastic") return TestKind::elastic;
  if (name == "triaxial") return TestKind::triaxial;
  return std::nullopt;
}

JobSpec parse_job(const nlohmann::json& job) {
  ObjectReader r(job, "");
  auto name = r.string("test");
  if (!name) throw SpecError("test", "is required (uct, btt, elastic or triaxial)");
  auto kind = test_kind_from_string(*name);
  if (!kind)
    throw SpecError("test", "unknown test '" + *name + "' (known: uct, btt, elastic, triaxial)");
  return parse_body(r, *kind);
}

JobSpec parse_job_template(const nlohmann::json& job_template, TestKind test,
                           const std::optional<BondSpec>& bond) {
  if (job_template.is_object() && job_template.contains("test")) {
    throw SpecError("job.test", "a template must not name the test; the campaign does");
  }
  ObjectReader r(job_template, "");
  return parse_body(r, test, bond);
}

nlohmann::json to_json(const JobSpec& s) {
  if (s.spec_effects_applied && !s.effects.empty())
    throw std::logic_error(
        "to_json: the spec has its effects applied; serialise the job as written");
  json j;
  j["test"] = to_string(s.test);
  j["sample"] = {{"diameter", s.sample.diameter_m},
                 {"height", s.sample.height_m},
                 {"thickness", s.sample.btt_thickness()},
                 {"packing", s.sample.packing},
                 {"radius_ratio", s.sample.radius_ratio},
                 {"radius", s.sample.radius_m},
                 {"seed", s.sample.seed}};
  if (s.sample.packing == "fcc") j["sample"]["lattice"] = s.sample.lattice;
  json mat = {{"density", s.material.density_kg_m3}, {"nu", s.material.nu}};
  if (s.material.kr_n_m) mat["kr"] = *s.material.kr_n_m;
  if (s.material.youngs_modulus_pa) mat["youngs_modulus"] = *s.material.youngs_modulus_pa;
  j["material"] = mat;
  j["bond"] = {{"fr0", s.bond.fr0_n}, {"fs0", s.bond.fs0_n}};
  j["contact"] = {{"friction", s.contact.friction}};
  json l = {{"dt_safety", s.loading.dt_safety},
            {"ramp_fraction", s.loading.ramp_fraction},
            {"stop_load_fraction", s.loading.stop_load_fraction},
            {"max_strain", s.loading.max_strain},
            {"platen_friction", s.loading.platen_friction},
            {"elastic_strain", s.loading.elastic_strain},
            {"slow_factor", s.loading.slow_factor},
            {"slow_trigger_broken_fraction", s.loading.slow_trigger_broken_fraction},
            {"rate_study", s.loading.rate_study},
            {"rate_study_runs", s.loading.rate_study_runs}};
  // A given speed keeps the canonical form it always had; "auto" carries its one parameter.
  if (s.loading.platen_velocity_m_s) {
    l["platen_velocity"] = *s.loading.platen_velocity_m_s;
  } else {
    l["platen_velocity"] = "auto";
    l["auto_transits"] = s.loading.auto_transits;
    l["past_window"] = s.loading.speed_up_past_window ? "speed_up" : "stop";
    // Absent when off, so that the identities of jobs from before it stay.
    if (s.loading.quasi_static_rerun) l["quasi_static_rerun"] = true;
    if (s.loading.follow_transits > 0) l["follow_transits"] = s.loading.follow_transits;
  }
  if (s.loading.dt_s)
    l["dt"] = *s.loading.dt_s;
  else
    l["dt"] = "auto";
  if (s.loading.max_steps) l["max_steps"] = *s.loading.max_steps;
  // Only where it may be given, so that the other tests' canonical forms (and job identities) stay.
  if (s.test == TestKind::triaxial) l["confining_pressure"] = s.loading.confining_pressure_pa;
  if (s.test != TestKind::elastic) {
    if (s.loading.seating_load_n)
      l["seating_load"] = *s.loading.seating_load_n;
    else
      l["seating_load"] = "auto";
  }
  if (s.test == TestKind::btt) {
    l["btt_geometry"] = to_string(s.loading.btt_geometry);
    if (s.loading.btt_geometry == BttGeometry::curved_jaws)
      l["jaw_radius_ratio"] = s.loading.jaw_radius_ratio;
    if (s.loading.btt_geometry == BttGeometry::flattened)
      l["flat_angle_deg"] = s.loading.flat_angle_deg;
  }
  j["loading"] = l;
  j["damping"] = {{"local", s.damping.local}, {"viscous", s.damping.viscous}};
  j["output"] = {{"vtk", s.output.vtk},
                 {"vtk_frames", s.output.vtk_frames},
                 {"curve_points", s.output.curve_points},
                 {"progress_seconds", s.output.progress_seconds}};
  if (!s.effects.empty())
    j["effects"] = s.effects;  // absent when none: identities of old jobs stay
  return j;
}

// Part of every job's identity in the job cache: it changes whenever a spec's results could.
const char* engine_version() {
  return "rockcal-dem 0.2.2";
}

}  // namespace rockcal
