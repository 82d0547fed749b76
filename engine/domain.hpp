// Spatial domain decomposition: slabs along the loading axis z, one per MPI rank, balanced by
// particle count at start-up. Particles near a slab border are mirrored as ghosts on the neighbour
// rank; bonds and contacts across a border are evaluated on both sides with the same operands, so
// both sides reach the same breakage decision without talking about it.
// A Domain with comm == MPI_COMM_NULL is the serial engine: no MPI call is ever made.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <limits>
#include <vector>

#include "engine/particles.hpp"

namespace rockcal {

struct Domain {
  MPI_Comm comm = MPI_COMM_NULL;
  int rank = 0, ranks = 1;
  double z_lo = -std::numeric_limits<double>::infinity();  // owned slab [z_lo, z_hi), m
  double z_hi = std::numeric_limits<double>::infinity();
  double halo = 0.0;                                 // ghost layer thickness, m
  int below = MPI_PROC_NULL, above = MPI_PROC_NULL;  // neighbour ranks
  std::vector<std::int32_t> send_below, send_above;  // owned particles mirrored as ghosts
  std::size_t ghosts_from_below = 0, ghosts_from_above = 0;
  // Per-step refresh buffers, kept so the time-step loop does not allocate.
  std::vector<double> out_below, out_above, in_below, in_above;

  bool parallel() const { return comm != MPI_COMM_NULL && ranks > 1; }
  bool root() const { return rank == 0; }
};

// Slabs balanced by the particles' z at start-up (every rank passes the same list). Throws when a
// slab would be thinner than the halo: too many ranks for the specimen.
Domain make_domain(MPI_Comm comm, std::vector<double> z_all, double halo);

// In-place reductions over all ranks (no-ops in serial).
void reduce_sum(const Domain& d, double* values, int n);
void reduce_max(const Domain& d, double* values, int n);
void reduce_min(const Domain& d, double* values, int n);
double sum_over_ranks(const Domain& d, double value);

// Exchanges a buffer with the rank below and the rank above: returns {from_below, from_above}.
struct Received {
  std::vector<double> from_below, from_above;
};
Received exchange(const Domain& d, const std::vector<double>& to_below,
                  const std::vector<double>& to_above);

// Copies the owners' current state (position, velocity, orientation, spin) into the ghosts.
void refresh_ghosts(Domain& d, Particles& p);

// Ghost records: what a neighbour needs to evaluate loads on its own particles.
constexpr int kGhostDoubles = 17;
void pack_ghost(const Particles& p, std::size_t k, std::vector<double>& out);
void unpack_ghost(const double* rec, Particles& p);  // appends a ghost
// Migrant records: a ghost record plus the platen friction history and the confinement flag.
constexpr int kMigrantDoubles = kGhostDoubles + 3 * kMaxWalls + 1;
void pack_migrant(const Particles& p, std::size_t k, std::vector<double>& out);
void unpack_migrant(const double* rec,
                    Particles& p);  // appends an owned particle (no ghosts present)

// Gathers variable-length buffers on rank 0 (others get an empty vector).
std::vector<double> gather_to_root(const Domain& d, const std::vector<double>& local);

}  // namespace rockcal
