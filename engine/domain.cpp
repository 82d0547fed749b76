#include "engine/domain.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rockcal {

Domain make_domain(MPI_Comm comm, std::vector<double> z_all, double halo) {
  Domain d;
  d.comm = comm;
  MPI_Comm_rank(comm, &d.rank);
  MPI_Comm_size(comm, &d.ranks);
  d.halo = halo;
  if (d.ranks == 1) return d;
  std::sort(z_all.begin(), z_all.end());
  const std::size_t n = z_all.size();
  // Borders at particle-count quantiles, moved to the gap below that layer so no particle sits on
  // one.
  std::vector<double> border(d.ranks + 1);
  border.front() = -std::numeric_limits<double>::infinity();
  border.back() = std::numeric_limits<double>::infinity();
  for (int r = 1; r < d.ranks; ++r) {
    const std::size_t k =
        std::min(n - 1, n * static_cast<std::size_t>(r) / static_cast<std::size_t>(d.ranks));
    const double z = z_all[k];
    auto lower = std::lower_bound(z_all.begin(), z_all.end(), z - 1e-9 * (1.0 + std::abs(z)));
    const double below = lower == z_all.begin() ? z - halo : *(lower - 1);
    border[r] = 0.5 * (below + z);
  }
  for (int r = 1; r + 1 < d.ranks; ++r) {
    if (border[r + 1] - border[r] < halo) {
      throw std::runtime_error("too many ranks for this specimen: a slab of " +
                               std::to_string(border[r + 1] - border[r]) +
                               " m is thinner than the halo of " + std::to_string(halo) + " m");
    }
  }
  d.z_lo = border[d.rank];
  d.z_hi = border[d.rank + 1];
  d.below = d.rank > 0 ? d.rank - 1 : MPI_PROC_NULL;
  d.above = d.rank + 1 < d.ranks ? d.rank + 1 : MPI_PROC_NULL;
  return d;
}

void reduce_sum(const Domain& d, double* v, int n) {
  if (d.parallel()) MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_SUM, d.comm);
}
void reduce_max(const Domain& d, double* v, int n) {
  if (d.parallel()) MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_MAX, d.comm);
}
void reduce_min(const Domain& d, double* v, int n) {
  if (d.parallel()) MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_MIN, d.comm);
}
double sum_over_ranks(const Domain& d, double value) {
  reduce_sum(d, &value, 1);
  return value;
}

namespace {

// One direction of a neighbour exchange: sizes first, then the data.
std::vector<double> shift(const Domain& d, const std::vector<double>& out, int to, int from,
                          int tag) {
  long long n_out = static_cast<long long>(out.size()), n_in = 0;
  MPI_Sendrecv(&n_out, 1, MPI_LONG_LONG, to, tag, &n_in, 1, MPI_LONG_LONG, from, tag, d.comm,
               MPI_STATUS_IGNORE);
  std::vector<double> in(static_cast<std::size_t>(n_in));
  MPI_Sendrecv(out.data(), static_cast<int>(n_out), MPI_DOUBLE, to, tag + 1, in.data(),
               static_cast<int>(n_in), MPI_DOUBLE, from, tag + 1, d.comm, MPI_STATUS_IGNORE);
  return in;
}

}  // namespace

Received exchange(const Domain& d, const std::vector<double>& to_below,
                  const std::vector<double>& to_above) {
  Received r;
  if (!d.parallel()) return r;
  r.from_above = shift(d, to_below, d.below, d.above, 10);
  r.from_below = shift(d, to_above, d.above, d.below, 20);
  return r;
}

namespace {

constexpr int kStateDoubles = 13;  // position, velocity, orientation, spin

void pack_state(const Particles& p, std::size_t k, double* o) {
  for (int a = 0; a < 3; ++a) {
    o[a] = p.pos[k][a];
    o[3 + a] = p.vel[k][a];
    o[10 + a] = p.omega[k][a];
  }
  o[6] = p.orient[k].w();
  o[7] = p.orient[k].x();
  o[8] = p.orient[k].y();
  o[9] = p.orient[k].z();
}

void unpack_state(const double* o, Particles& p, std::size_t k) {
  p.pos[k] = Vec3(o[0], o[1], o[2]);
  p.vel[k] = Vec3(o[3], o[4], o[5]);
  p.orient[k] = Quat(o[6], o[7], o[8], o[9]);
  p.omega[k] = Vec3(o[10], o[11], o[12]);
}

void pack_states(const Particles& p, const std::vector<std::int32_t>& list,
                 std::vector<double>& out) {
  out.resize(list.size() * kStateDoubles);
  for (std::size_t m = 0; m < list.size(); ++m)
    pack_state(p, static_cast<std::size_t>(list[m]), &out[m * kStateDoubles]);
}

// Fixed-size variant of `shift` for the per-step refresh: both sides know the counts.
void shift_states(const Domain& d, const std::vector<double>& out, int to, int from, double* in,
                  std::size_t n_in, int tag) {
  MPI_Sendrecv(out.data(), static_cast<int>(out.size()), MPI_DOUBLE, to, tag, in,
               static_cast<int>(n_in), MPI_DOUBLE, from, tag, d.comm, MPI_STATUS_IGNORE);
}

}  // namespace

void refresh_ghosts(Domain& d, Particles& p) {
  if (!d.parallel()) return;
  const std::size_t first_below = p.n_owned, first_above = p.n_owned + d.ghosts_from_below;
  d.in_above.resize(d.ghosts_from_above * kStateDoubles);
  d.in_below.resize(d.ghosts_from_below * kStateDoubles);
  pack_states(p, d.send_below, d.out_below);
  pack_states(p, d.send_above, d.out_above);
  shift_states(d, d.out_below, d.below, d.above, d.in_above.data(), d.in_above.size(), 30);
  shift_states(d, d.out_above, d.above, d.below, d.in_below.data(), d.in_below.size(), 31);
  for (std::size_t m = 0; m < d.ghosts_from_below; ++m)
    unpack_state(&d.in_below[m * kStateDoubles], p, first_below + m);
  for (std::size_t m = 0; m < d.ghosts_from_above; ++m)
    unpack_state(&d.in_above[m * kStateDoubles], p, first_above + m);
}

void pack_ghost(const Particles& p, std::size_t k, std::vector<double>& out) {
  const std::size_t at = out.size();
  out.resize(at + kGhostDoubles);
  pack_state(p, k, &out[at]);
  out[at + 13] = p.radius[k];
  out[at + 14] = p.mass[k];
  out[at + 15] = p.inertia[k];
  out[at + 16] = static_cast<double>(p.id[k]);  // ids stay far below 2^53
}

void unpack_ghost(const double* rec, Particles& p) {
  const std::size_t owned = p.n_owned;
  p.add(Vec3::Zero(), rec[13], rec[14], rec[15], static_cast<std::int64_t>(rec[16]));
  p.n_owned = owned;
  unpack_state(rec, p, p.size() - 1);
}

void pack_migrant(const Particles& p, std::size_t k, std::vector<double>& out) {
  pack_ghost(p, k, out);
  for (int w = 0; w < kMaxWalls; ++w)
    for (int a = 0; a < 3; ++a) out.push_back(p.wall_spring[k][w][a]);
  out.push_back(p.confined[k]);
}

void unpack_migrant(const double* rec, Particles& p) {
  unpack_ghost(rec, p);
  p.n_owned = p.size();  // migrants join the owned block (ghosts are dropped before they arrive)
  for (int w = 0; w < kMaxWalls; ++w)
    p.wall_spring.back()[w] = Vec3(rec[kGhostDoubles + 3 * w], rec[kGhostDoubles + 3 * w + 1],
                                   rec[kGhostDoubles + 3 * w + 2]);
  p.confined.back() = rec[kGhostDoubles + 3 * kMaxWalls] != 0.0 ? 1 : 0;
}

std::vector<double> gather_to_root(const Domain& d, const std::vector<double>& local) {
  if (!d.parallel()) return local;
  int n = static_cast<int>(local.size());
  std::vector<int> counts(d.root() ? d.ranks : 0), offsets;
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, d.comm);
  std::vector<double> all;
  if (d.root()) {
    offsets.assign(d.ranks, 0);
    for (int r = 1; r < d.ranks; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
    all.resize(static_cast<std::size_t>(offsets.back() + counts.back()));
  }
  MPI_Gatherv(local.data(), n, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE, 0,
              d.comm);
  return all;
}

}  // namespace rockcal
