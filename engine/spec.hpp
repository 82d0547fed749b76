// The job spec: the only way anything talks to the engine. SI units throughout.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/effects/effect.hpp"

namespace rockcal {

// triaxial: the UCT cylinder with a confining pressure on its lateral surface.
enum class TestKind { uct, btt, elastic, triaxial };

// How the Brazilian disc is loaded (docs/specimens.md). flat_platens: the full disc between flat
// platens (the seed paper's set-up; the contact width is whatever the particle cut leaves);
// curved_jaws: ISRM's suggested method, concave jaws of jaw_radius_ratio x the disc radius;
// flattened: two parallel flats cut at the loading angle 2 alpha (Wang et al. 2004), flat platens.
enum class BttGeometry { flat_platens, curved_jaws, flattened };

// Per-job cost limits (docs/engine-interface.md, "Limits"): no single job may ask for more. The
// job's wall time is bounded by whoever runs it (the service's --job-timeout).
inline constexpr double kMaxParticles = 2.0e6;            // memory: about 2 KB per particle
inline constexpr std::int64_t kMaxSteps = 100'000'000;    // loading.max_steps
inline constexpr std::int64_t kMaxCurvePoints = 100'000;  // output.curve_points (rows stored)
inline constexpr std::int64_t kMaxVtkFrames = 1'000;      // output.vtk_frames
inline constexpr double kMaxVtkParticleFrames = 5.0e7;    // vtk_frames x particles (disk)

// An invalid spec. `field` is the dotted path of the offending key ("loading.dt").
struct SpecError : std::runtime_error {
  std::string field;
  std::string message;  // what() without the "field: " prefix (what() stops at a NUL in a key)
  SpecError(std::string field_path, const std::string& text)
      : std::runtime_error(field_path + ": " + text), field(std::move(field_path)), message(text) {}
};

struct SampleSpec {
  double diameter_m = 10.0;
  double height_m = 28.0;             // UCT and elastic specimen length
  std::optional<double> thickness_m;  // BTT disc thickness; default diameter / 2
  std::string packing = "fcc";        // "fcc" or "random" (random dense, polydisperse)
  double radius_m = 1.0;              // particle radius (mean radius for random packings)
  double radius_ratio = 1.0;          // random packings: max / min radius (uniform in between)
  std::uint64_t seed = 1;
  // FCC only: "seeded" places the lattice by the seed (a random offset within a cell and a turn
  // about the loading axis), so replicates are different cuts; "aligned" is the seed paper's cut
  // (a centre at the origin, cube axes along x, y, z), the same for every seed.
  std::string lattice = "seeded";
  double btt_thickness() const { return thickness_m.value_or(0.5 * diameter_m); }
  // Equal specimens: a thickness left to its default equals the same thickness given (the
  // canonical form gives it).
  bool operator==(const SampleSpec& o) const {
    return diameter_m == o.diameter_m && height_m == o.height_m &&
           btt_thickness() == o.btt_thickness() && packing == o.packing && radius_m == o.radius_m &&
           radius_ratio == o.radius_ratio && seed == o.seed && lattice == o.lattice;
  }
};

struct MaterialSpec {
  double density_kg_m3 = 1.0;
  std::optional<double> kr_n_m;             // normal bond stiffness given directly ...
  std::optional<double> youngs_modulus_pa;  // ... or derived from E by eq. 3 (exactly one of them)
  double nu = 0.2;
  bool operator==(const MaterialSpec&) const = default;
};

struct BondSpec {
  double fr0_n = 64.0;  // tensile strength
  double fs0_n = 64.0;  // shear strength
  // Bonds join pairs whose centres lie within reach x (R_i + R_j): 1 bonds touching neighbours
  // only. Not a job field: the interaction_range effect sets it.
  double reach = 1.0;
  bool operator==(const BondSpec&) const = default;
};

struct ContactSpec {
  double friction = 0.6;  // particle-particle Coulomb coefficient
  bool operator==(const ContactSpec&) const = default;
};

constexpr double kBttMaxStrain = 0.1;

struct LoadingSpec {
  // Each platen moves at this speed towards the centre. nullopt = "auto": the speed follows from
  // the bonds' failure strain so that the platens close by it in auto_transits elastic-wave
  // transits (loadtests/loading_speed.hpp); use platen_speed() for the speed a run uses.
  std::optional<double> platen_velocity_m_s = 0.05;
  double auto_transits = 20.0;  // "auto" speed only
  // "auto" speed only: past the bond-controlled window (loadtests/loading_speed.hpp) a load that
  // still rises is a crushed specimen's, not a strength. false ("stop"): the run ends there without
  // a peak; true ("speed_up"): the platens speed up and a later maximum is reported as a late peak.
  bool speed_up_past_window = false;
  // "auto" speed only: a UCT, BTT or triaxial (the elastic test ignores it; a calibration's
  // template serves both) whose peak came in fewer wave transits than the
  // quasi-static threshold runs again once, with auto_transits raised so that the same peak
  // would come at kRerunMargin times the threshold (loadtests/quasi_static_rerun.hpp).
  bool quasi_static_rerun = false;
  // "auto" speed only, 0 = off: the platens never close slower than the closure since seating
  // over this many wave transits (loadtests/loading_speed.hpp, follow_rate): a peak that comes
  // many bond failure strains in is reached at the same relative rate, not after as many transits
  // per failure strain as the first bond took.
  double follow_transits = 0.0;
  std::optional<double> dt_s;   // nullopt = "auto"
  double dt_safety = 0.5;       // fraction of the critical step used by "auto"
  double ramp_fraction = 0.01;  // speed ramps over this fraction of the run (>= 2 wave transits)
  double stop_load_fraction = 0.7;  // stop once the load falls to this fraction of the peak
  double max_strain = 0.05;         // stop at this platen strain (total closure / length);
                                    // the BTT's default is kBttMaxStrain
  std::optional<std::int64_t> max_steps;
  double platen_friction = 0.0;  // Coulomb coefficient between platen and particles
  // Seating: the platens close until the load reaches this, hold still while the specimen
  // settles, and the measured loading (curve, modulus, peak) starts from there. nullopt = auto
  // (seating_load_auto in loadtests/seating.hpp).
  std::optional<double> seating_load_n;
  // BTT only (test parameters of the Brazilian set-up).
  // The default, a flattened disc of 2 alpha = 30 degrees, is the set-up whose discs split from
  // the centre in the convergence study (docs/specimens.md).
  BttGeometry btt_geometry = BttGeometry::flattened;
  double jaw_radius_ratio = 1.5;  // curved jaws: jaw radius / disc radius (ISRM: 1.5)
  double flat_angle_deg = 30.0;   // flattened: loading angle 2 alpha of the flats, degrees
  // Triaxial test only: pressure on the lateral surface, ramped in before the platens advance.
  double confining_pressure_pa = 0.0;
  double elastic_strain = 2e-4;  // elastic test: the applied axial strain
  // Two-rate loading (the seed paper's proposal): once this fraction of the bonds has broken, the
  // platens slow down to slow_factor x platen_velocity. 1 = a single rate.
  double slow_factor = 1.0;
  double slow_trigger_broken_fraction = 1e-3;
  // Rate study: repeat the test at decreasing speeds and extrapolate the peak to zero speed.
  bool rate_study = false;
  std::int64_t rate_study_runs = 3;
  bool operator==(const LoadingSpec&) const = default;
};

struct DampingSpec {
  double local = 0.7;    // Cundall non-viscous coefficient, [0, 1)
  double viscous = 0.0;  // mass-proportional viscous damping rate, 1/s
  bool operator==(const DampingSpec&) const = default;
};

struct OutputSpec {
  bool vtk = false;                  // write particle and broken-bond VTK files
  std::int64_t vtk_frames = 10;      // number of VTK snapshots over the run
  std::int64_t curve_points = 2000;  // approximate rows in curve.csv
  double progress_seconds = 2.0;     // period of progress reports
  bool operator==(const OutputSpec&) const = default;
};

struct JobSpec {
  TestKind test = TestKind::uct;
  SampleSpec sample;
  MaterialSpec material;
  BondSpec bond;
  ContactSpec contact;
  LoadingSpec loading;
  DampingSpec damping;
  OutputSpec output;
  // Optional physics effects (effects/effect.hpp) by name, each with all its parameters. Part of
  // the job as written: the fields above keep what the job gave, and effective_spec() applies the
  // effects' spec hooks for a run.
  std::map<std::string, EffectValues> effects;
  bool spec_effects_applied = false;  // set by effective_spec(); such a spec is not serialised
  bool operator==(const JobSpec&) const = default;
};

// Parses and validates a job. Throws SpecError naming the first offending field.
JobSpec parse_job(const nlohmann::json& job);

// Parses a job template that has no "test" key yet (the service adds it per job). Same checks.
// With `bond`, the job's strengths are these (the campaign sets them): the template's own "bond"
// block, if any, may only name fr0 and fs0, whose values are ignored. So a campaign validates its
// template as it stands, without copying it to fill in a bond.
JobSpec parse_job_template(const nlohmann::json& job_template, TestKind test,
                           const std::optional<BondSpec>& bond = std::nullopt);

// The canonical form: every field present with its default, so that equal jobs serialise equally.
// It is the job as written (effects not applied), so parse_job(to_json(s)) == s. Throws
// std::logic_error for an effective spec with effects: parsing that would apply them twice.
nlohmann::json to_json(const JobSpec& spec);

const char* to_string(TestKind test);
std::optional<TestKind> test_kind_from_string(const std::string& name);
const char* to_string(BttGeometry geometry);
std::optional<BttGeometry> btt_geometry_from_string(const std::string& name);

// Engine version; part of a job's identity (a changed engine invalidates cached results).
const char* engine_version();

}  // namespace rockcal
