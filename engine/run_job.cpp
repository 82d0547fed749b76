#include "engine/run_job.hpp"

#include <cstdio>

#include "engine/loadtests/driver.hpp"
#include "engine/output.hpp"
#include "engine/simulation.hpp"

namespace rockcal {

namespace fs = std::filesystem;

nlohmann::json run_job(const JobSpec& spec, const fs::path& dir, const std::atomic<bool>* stop,
                       bool progress_on_stderr) {
  fs::create_directories(dir);
  RunHooks hooks;
  hooks.stop = stop;
  hooks.on_progress = [&](const Progress& p) {
    write_atomically(dir / "progress.json", progress_to_json(p).dump() + "\n");
    if (progress_on_stderr) {
      std::fprintf(stderr,
                   "[rockcal-dem] %5.1f%%  step %lld  load %.6g  peak %.6g  broken %lld  %.1f s\n",
                   100.0 * p.fraction, static_cast<long long>(p.step), p.load_n, p.peak_load_n,
                   static_cast<long long>(p.broken_bonds), p.elapsed_s);
    }
  };
  if (spec.output.vtk) {
    fs::create_directories(dir / "vtk");
    hooks.on_frame = [&](const Simulation& sim, int frame) {
      char name[32];
      std::snprintf(name, sizeof name, "particles_%04d.vtu", frame);
      write_particles_vtu(dir / "vtk" / name, sim);
    };
  }

  const TestResult r = run_test(spec, hooks);
  write_curve_csv(dir / "curve.csv", r.curve);
  write_breaks_csv(dir / "breaks.csv", r.breaks);
  if (spec.output.vtk) write_breaks_vtu(dir / "vtk" / "breaks.vtu", r.breaks);
  nlohmann::json result = result_to_json(spec, r, 1);
  if (progress_on_stderr) {
    std::fprintf(stderr,
                 "[rockcal-dem] %s: peak load %.6g N, strength %.6g Pa, %lld particles, %lld of "
                 "%lld bonds broken, "
                 "%lld steps in %.2f s (%s)\n",
                 to_string(spec.test), r.peak_load_n, r.strength_pa,
                 static_cast<long long>(r.particles), static_cast<long long>(r.broken_bonds),
                 static_cast<long long>(r.bonds), static_cast<long long>(r.steps), r.wall_seconds,
                 r.stop_reason.c_str());
  }
  if (r.stop_reason != "cancelled") write_atomically(dir / "result.json", result.dump(2) + "\n");
  return result;
}

}  // namespace rockcal
