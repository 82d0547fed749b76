#include "engine/output.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "engine/loadtests/brazilian.hpp"
#include "engine/loadtests/strength.hpp"
#include "engine/simulation.hpp"

namespace rockcal {

namespace fs = std::filesystem;

nlohmann::json result_to_json(const JobSpec& spec, const TestResult& r, int ranks) {
  using nlohmann::json;
  auto opt = [](const std::optional<double>& v) { return v ? json(*v) : json(nullptr); };
  const double wall = std::max(r.wall_seconds, 1e-9);
  json by;
  for (int m = 0; m < 4; ++m) by[to_string(static_cast<BreakMode>(m))] = r.broken_by[m];
  json rate = nullptr;
  if (r.rate_study) {
    rate = {{"speeds", r.rate_study->speeds_m_s},
            {"peak_loads", r.rate_study->peaks_n},
            {"wall_seconds", r.rate_study->wall_seconds},
            {"extrapolated_peak_load", r.rate_study->extrapolated_peak_n},
            {"rate_error", r.rate_study->rate_error},
            {"converged", r.rate_study->converged}};
  }
  json out{{"test", to_string(r.test)},
           {"peak_load", r.peak_load_n},
           {"strength", r.strength_pa},
           {"confining_pressure", r.confining_pressure_pa},
           {"youngs_modulus", opt(r.youngs_modulus_pa)},
           {"poisson_ratio", opt(r.poisson_ratio)},
           {"gauge_modulus", opt(r.gauge_modulus_pa)},
           {"peak_displacement", r.peak_displacement_m},
           {"peak_strain", opt(r.peak_strain)},
           {"particles", r.particles},
           {"bonds", r.bonds},
           {"broken_bonds", r.broken_bonds},
           {"broken_bonds_at_peak", r.broken_at_peak},
           {"broken_by", by},
           {"steps", r.steps},
           {"dt", r.dt_s},
           {"wall_seconds", r.wall_seconds},
           {"particle_steps_per_second", double(r.particles) * double(r.steps) / wall},
           {"stop_reason", r.stop_reason},
           {"floaters_removed", r.floaters_removed},
           {"engine_version", engine_version()},
           {"ranks", ranks},
           {"rate_study", rate},
           {"spec", to_json(spec)}};
  if (r.test == TestKind::elastic) return out;
  // Loading tests: whether the peak is a failure, how the strength follows from it, from which
  // state it was measured, and (BTT) the set-up's strength factor and where the disc broke first.
  out["peak_reached"] = r.peak_reached;
  if (const auto definition = strength_definition(spec))
    out["strength_definition"] = to_json(*definition);
  if (!r.peak_reached) out["no_peak_reason"] = r.no_peak_reason;
  out["peak_step"] = r.peak_step;  // breaks.csv rows up to it are the damage at the peak
  if (r.loading_rate) {
    const LoadingRate& q = *r.loading_rate;
    out["loading_rate"] = {
        {"platen_velocity", q.platen_velocity_m_s},
        {"auto", q.automatic},
        {"bond_failure_strain", q.bond_failure_strain},
        {"wave_transit_time", q.wave_transit_s},
        {"peak_transits", r.peak_reached ? json(q.peak_transits) : json()},
        {"kinetic_energy_ratio", r.peak_reached ? json(q.kinetic_energy_ratio) : json()},
        {"quasi_static_transits", q.min_transits},
        {"quasi_static", r.peak_reached ? json(q.quasi_static()) : json()},
        {"late_velocity", q.late_velocity_m_s > 0 ? json(q.late_velocity_m_s) : json()},
        {"late_peak", r.peak_reached ? json(q.late_peak) : json()},
        {"follow_transits", q.follow_transits > 0 ? json(q.follow_transits) : json()},
        {"followed", r.peak_reached && q.follow_transits > 0 ? json(q.followed) : json()},
        {"rerun", q.rerun ? json{{"first_peak_transits", q.rerun->first_peak_transits},
                                 {"first_peak_load", q.rerun->first_peak_load_n},
                                 {"auto_transits", q.rerun->auto_transits}}
                          : json()}};
  }
  out["seating"] = {{"load", r.seating.load_n},
                    {"closure", r.seating.closure_m},
                    {"step", r.seating.step},
                    {"broken_bonds", r.seating.broken_bonds}};
  if (r.test == TestKind::btt) {
    json btt = {{"geometry", to_string(spec.loading.btt_geometry)},
                {"strength_factor", btt_strength_factor(spec.loading)}};
    if (r.btt_fracture) {
      const BttFracture& f = *r.btt_fracture;
      btt["rim_breaks_before_peak"] = f.rim_breaks_before_peak;
      btt["first_interior_breaks"] = {{"count", f.first_count},
                                      {"median_r_over_R", f.first_median_r_over_R},
                                      {"max_r_over_R", f.first_max_r_over_R}};
      btt["loaded_band_fraction"] = f.loaded_band_fraction;
      btt["centre_split"] = f.centre_split;
    }
    out["btt"] = btt;
  }
  return out;
}

void write_atomically(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
    out << text;
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  fs::rename(tmp, path);
}

void write_curve_csv(const fs::path& path, const std::vector<CurvePoint>& curve) {
  std::ofstream out(path);
  out << "step,time_s,displacement_m,load_n,broken_bonds,lateral_strain\n";
  out.precision(10);
  for (const CurvePoint& c : curve) {
    out << c.step << ',' << c.time_s << ',' << c.displacement_m << ',' << c.load_n << ','
        << c.broken_bonds << ',';
    if (c.lateral_strain) out << *c.lateral_strain;
    out << '\n';
  }
}

void write_breaks_csv(const fs::path& path, const std::vector<BreakEvent>& breaks) {
  std::ofstream out(path);
  out << "step,x,y,z,mode\n";
  out.precision(10);
  for (const BreakEvent& b : breaks)
    out << b.step << ',' << b.where.x() << ',' << b.where.y() << ',' << b.where.z() << ','
        << to_string(b.mode) << '\n';
}

nlohmann::json progress_to_json(const Progress& p) {
  return {{"step", p.step},
          {"fraction", p.fraction},
          {"load", p.load_n},
          {"peak_load", p.peak_load_n},
          {"broken_bonds", p.broken_bonds},
          {"elapsed_s", p.elapsed_s}};
}

namespace {

// Minimal VTK XML unstructured grid of vertices with point data arrays (ASCII, ParaView reads it).
class VtuWriter {
 public:
  explicit VtuWriter(const fs::path& path) : out_(path) {
    if (!out_) throw std::runtime_error("cannot write " + path.string());
    out_.precision(9);
  }
  // `fields`: one value each for the whole snapshot (VTK field data), e.g. its time and load.
  void begin(std::size_t n, const std::vector<std::pair<const char*, double>>& fields = {}) {
    n_ = n;
    out_ << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
            "byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n";
    if (!fields.empty()) {
      out_ << "<FieldData>\n";
      for (const auto& [name, value] : fields)
        out_ << "<DataArray type=\"Float64\" Name=\"" << name
             << "\" NumberOfTuples=\"1\" format=\"ascii\">" << value << "</DataArray>\n";
      out_ << "</FieldData>\n";
    }
    out_ << "<Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n << "\">\n";
  }
  template <class F>
  void points(F point_at) {
    out_ << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (std::size_t k = 0; k < n_; ++k) {
      const Vec3 x = point_at(k);
      out_ << x.x() << ' ' << x.y() << ' ' << x.z() << '\n';
    }
    out_ << "</DataArray></Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" "
            "format=\"ascii\">\n";
    for (std::size_t k = 0; k < n_; ++k) out_ << k << '\n';
    out_ << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t k = 0; k < n_; ++k) out_ << k + 1 << '\n';
    out_ << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (std::size_t k = 0; k < n_; ++k) out_ << "1\n";  // VTK_VERTEX
    out_ << "</DataArray>\n</Cells>\n<PointData>\n";
  }
  template <class F>
  void scalars(const char* name, F value_at) {
    out_ << "<DataArray type=\"Float64\" Name=\"" << name << "\" format=\"ascii\">\n";
    for (std::size_t k = 0; k < n_; ++k) out_ << value_at(k) << '\n';
    out_ << "</DataArray>\n";
  }
  template <class F>
  void vectors(const char* name, F value_at) {
    out_ << "<DataArray type=\"Float64\" Name=\"" << name
         << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (std::size_t k = 0; k < n_; ++k) {
      const Vec3 v = value_at(k);
      out_ << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    }
    out_ << "</DataArray>\n";
  }
  void end() { out_ << "</PointData>\n</Piece></UnstructuredGrid>\n</VTKFile>\n"; }

 private:
  std::ofstream out_;
  std::size_t n_ = 0;
};

}  // namespace

void write_particles_vtu(const fs::path& path, const Simulation& sim, const Frame& frame) {
  const Particles& p = sim.particles;
  std::vector<int> broken_count(p.size(), 0);
  for (const Bond& b : sim.broken) {
    ++broken_count[b.i];
    ++broken_count[b.j];
  }
  VtuWriter w(path);
  w.begin(p.size(), {{"TimeValue", frame.time_s},
                     {"step", double(frame.step)},
                     {"load", frame.load_n},
                     {"displacement", frame.displacement_m}});
  w.points([&](std::size_t k) { return p.pos[k]; });
  w.scalars("radius", [&](std::size_t k) { return p.radius[k]; });
  w.scalars("id", [&](std::size_t k) { return double(p.id[k]); });
  w.scalars("broken_bonds", [&](std::size_t k) { return double(broken_count[k]); });
  w.vectors("velocity", [&](std::size_t k) { return p.vel[k]; });
  w.end();
}

void write_breaks_vtu(const fs::path& path, const std::vector<BreakEvent>& breaks) {
  VtuWriter w(path);
  w.begin(breaks.size());
  w.points([&](std::size_t k) { return breaks[k].where; });
  w.scalars("step", [&](std::size_t k) { return double(breaks[k].step); });
  w.scalars("mode", [&](std::size_t k) { return double(static_cast<int>(breaks[k].mode)); });
  w.end();
}

std::string particles_vtu_name(int frame, int rank, int ranks) {
  char name[48];
  if (ranks > 1)
    std::snprintf(name, sizeof name, "particles_%04d_r%d.vtu", frame, rank);
  else
    std::snprintf(name, sizeof name, "particles_%04d.vtu", frame);
  return name;
}

void write_vtk_series(const fs::path& path, const std::vector<Frame>& frames, int ranks) {
  std::ostringstream out;
  out.precision(10);
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" "
         "byte_order=\"LittleEndian\">\n<Collection>\n";
  for (const Frame& f : frames) {
    for (int rank = 0; rank < ranks; ++rank) {
      out << "<DataSet timestep=\"" << f.time_s << "\" part=\"" << rank << "\" file=\""
          << particles_vtu_name(f.index, rank, ranks) << "\" step=\"" << f.step << "\" load=\""
          << f.load_n << "\" displacement=\"" << f.displacement_m << "\"/>\n";
    }
  }
  out << "</Collection>\n</VTKFile>\n";
  write_atomically(path, out.str());
}

}  // namespace rockcal
