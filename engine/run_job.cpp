#include "engine/run_job.hpp"

#include <algorithm>
#include <cstdio>

#include "engine/loadtests/driver.hpp"
#include "engine/output.hpp"
#include "engine/simulation.hpp"

namespace rockcal {

namespace fs = std::filesystem;

namespace {

// Every rank's break events, on rank 0.
std::vector<BreakEvent> gather_breaks(const Domain& d, const std::vector<BreakEvent>& local) {
  std::vector<double> flat;
  for (const BreakEvent& e : local)
    flat.insert(flat.end(), {double(e.step), double(e.id_i), double(e.id_j), e.where.x(),
                             e.where.y(), e.where.z(), double(static_cast<int>(e.mode))});
  const std::vector<double> all = gather_to_root(d, flat);
  std::vector<BreakEvent> out;
  for (std::size_t k = 0; k + 7 <= all.size(); k += 7)
    out.push_back({static_cast<std::int64_t>(all[k]), static_cast<std::int64_t>(all[k + 1]),
                   static_cast<std::int64_t>(all[k + 2]), Vec3(all[k + 3], all[k + 4], all[k + 5]),
                   static_cast<BreakMode>(static_cast<int>(all[k + 6]))});
  std::sort(out.begin(), out.end(),
            [](const BreakEvent& a, const BreakEvent& b) { return a.step < b.step; });
  return out;
}

}  // namespace

nlohmann::json run_job(const JobSpec& spec, const fs::path& dir, const std::atomic<bool>* stop,
                       bool progress_on_stderr, MPI_Comm comm) {
  int rank = 0, ranks = 1;
  if (comm != MPI_COMM_NULL) {
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &ranks);
  }
  const bool root = rank == 0;
  if (root) fs::create_directories(dir);
  RunHooks hooks;
  std::vector<Frame> frames;  // the VTK snapshots written, for their series
  hooks.comm = ranks > 1 ? comm : MPI_COMM_NULL;
  hooks.stop = stop;
  if (root) {
    hooks.on_progress = [&](const Progress& p) {
      write_atomically(dir / "progress.json", progress_to_json(p).dump() + "\n");
      if (progress_on_stderr) {
        std::fprintf(
            stderr, "[rockcal-dem] %5.1f%%  step %lld  load %.6g  peak %.6g  broken %lld  %.1f s\n",
            100.0 * p.fraction, static_cast<long long>(p.step), p.load_n, p.peak_load_n,
            static_cast<long long>(p.broken_bonds), p.elapsed_s);
      }
    };
  }
  if (spec.output.vtk) {
    if (root) fs::create_directories(dir / "vtk");
    if (ranks > 1) MPI_Barrier(comm);
    hooks.on_frame = [&, rank, ranks](const Simulation& sim, const Frame& frame) {
      write_particles_vtu(dir / "vtk" / particles_vtu_name(frame.index, rank, ranks), sim, frame);
      if (frame.index == 0) frames.clear();  // a rate study's next run writes its frames afresh
      frames.push_back(frame);
    };
  }

  TestResult r = run_test(spec, hooks);
  if (ranks > 1) {
    Domain world;
    world.comm = comm;
    world.rank = rank;
    world.ranks = ranks;
    r.breaks = gather_breaks(world, r.breaks);
    // The drivers counted from this rank's breaks only; count them again from all.
    tally_breaks(spec, r);
  }
  nlohmann::json result = result_to_json(spec, r, ranks);
  if (!root) return result;

  write_curve_csv(dir / "curve.csv", r.curve);
  write_breaks_csv(dir / "breaks.csv", r.breaks);
  if (spec.output.vtk) {
    write_breaks_vtu(dir / "vtk" / "breaks.vtu", r.breaks);
    write_vtk_series(dir / "vtk" / "particles.pvd", frames, ranks);
  }
  if (progress_on_stderr) {
    std::fprintf(stderr,
                 "[rockcal-dem] %s: peak load %.6g N, strength %.6g Pa, %lld particles, %lld of "
                 "%lld bonds broken, "
                 "%lld steps in %.2f s on %d rank(s) (%s)\n",
                 to_string(spec.test), r.peak_load_n, r.strength_pa,
                 static_cast<long long>(r.particles), static_cast<long long>(r.broken_bonds),
                 static_cast<long long>(r.bonds), static_cast<long long>(r.steps), r.wall_seconds,
                 ranks, r.stop_reason.c_str());
  }
  if (r.stop_reason != "cancelled") write_atomically(dir / "result.json", result.dump(2) + "\n");
  return result;
}

}  // namespace rockcal
