#include "engine/neighbours.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace rockcal {
namespace {

// Bond partners of each local particle in CSR form (both directions), for lookups during the build.
struct Adjacency {
  std::vector<std::int32_t> offset, partner;
  std::vector<PairBond> state;

  Adjacency(std::size_t n, const std::vector<Bond>& intact, const std::vector<Bond>& broken) {
    offset.assign(n + 1, 0);
    auto count = [&](const std::vector<Bond>& bs) {
      for (const Bond& b : bs) {
        ++offset[b.i + 1];
        ++offset[b.j + 1];
      }
    };
    count(intact);
    count(broken);
    for (std::size_t k = 0; k < n; ++k) offset[k + 1] += offset[k];
    partner.resize(offset[n]);
    state.resize(offset[n]);
    std::vector<std::int32_t> fill(offset.begin(), offset.end() - 1);
    auto put = [&](const std::vector<Bond>& bs, PairBond s) {
      for (const Bond& b : bs) {
        partner[fill[b.i]] = b.j;
        state[fill[b.i]++] = s;
        partner[fill[b.j]] = b.i;
        state[fill[b.j]++] = s;
      }
    };
    put(intact, PairBond::intact);
    put(broken, PairBond::broken);
  }

  PairBond lookup(std::int32_t a, std::int32_t b) const {
    PairBond s = PairBond::none;
    for (std::int32_t k = offset[a]; k < offset[a + 1]; ++k)
      if (partner[k] == b) s = std::max(s, state[k]);  // a re-formed bond would not be "broken"
    return s;
  }
};

bool id_less(const SpringRecord& a, const SpringRecord& b) {
  return a.id_lo < b.id_lo || (a.id_lo == b.id_lo && a.id_hi < b.id_hi);
}

}  // namespace

bool NeighbourList::needs_rebuild(const Particles& p) const {
  if (ref_pos.size() != p.n_owned) return true;
  const double limit2 = 0.25 * skin * skin;
  for (std::size_t k = 0; k < p.n_owned; ++k)
    if ((p.pos[k] - ref_pos[k]).squaredNorm() > limit2) return true;
  return false;
}

void NeighbourList::build(const Particles& p, const std::vector<Bond>& intact,
                          const std::vector<Bond>& broken,
                          const std::vector<SpringRecord>& incoming) {
  const std::size_t n = p.size();
  // History carried over by ids: springs of the old list, plus what migrants brought along.
  std::vector<SpringRecord> history = incoming;
  for (const ContactPair& c : pairs) {
    const SpringRecord r{p_id_cache_[c.i], p_id_cache_[c.j], c.spring, c.roll};
    if (!r.empty()) history.push_back(r);
  }
  std::sort(history.begin(), history.end(), id_less);
  pairs.clear();
  ref_pos.assign(p.pos.begin(), p.pos.begin() + static_cast<std::ptrdiff_t>(p.n_owned));
  p_id_cache_ = p.id;
  ++builds;
  if (n == 0) return;

  Vec3 lo = p.pos[0], hi = p.pos[0];
  double r_max = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    lo = lo.cwiseMin(p.pos[k]);
    hi = hi.cwiseMax(p.pos[k]);
    r_max = std::max(r_max, p.radius[k]);
  }
  const double cell = 2.0 * r_max + skin;
  // A grain thrown off the specimen would stretch a box over all particles to millions of empty
  // cells, rebuilt every step while it flies. The grid covers the bulk (around the median, three
  // times the 10th-90th percentile spread) and clamps the few outside into its border cells:
  // clamping never separates two particles closer than a cell, so every pair within reach is
  // still found.
  std::vector<double> coord(n);
  for (int a = 0; a < 3; ++a) {
    for (std::size_t k = 0; k < n; ++k) coord[k] = p.pos[k][a];
    const auto quantile = [&](double f) {
      auto it = coord.begin() + static_cast<std::ptrdiff_t>(f * static_cast<double>(n - 1));
      std::nth_element(coord.begin(), it, coord.end());
      return *it;
    };
    const double q10 = quantile(0.1), q90 = quantile(0.9), mid = quantile(0.5);
    const double half = 1.5 * (q90 - q10) + 2.0 * cell;
    lo[a] = std::max(lo[a], mid - half);
    hi[a] = std::min(hi[a], mid + half);
  }
  std::array<std::int64_t, 3> dims;
  for (int a = 0; a < 3; ++a)
    dims[a] = std::max<std::int64_t>(1, static_cast<std::int64_t>((hi[a] - lo[a]) / cell) + 1);
  auto cell_of = [&](const Vec3& x, int a) {
    return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((x[a] - lo[a]) / cell)), 0,
                                    dims[a] - 1);
  };
  const std::size_t ncell = static_cast<std::size_t>(dims[0] * dims[1] * dims[2]);
  std::vector<std::int32_t> start(ncell + 1, 0), members(n);
  std::vector<std::int64_t> home(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& x = p.pos[k];
    home[k] = (cell_of(x, 2) * dims[1] + cell_of(x, 1)) * dims[0] + cell_of(x, 0);
    ++start[home[k] + 1];
  }
  for (std::size_t c = 0; c < ncell; ++c) start[c + 1] += start[c];
  {
    std::vector<std::int32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < n; ++k) members[fill[home[k]]++] = static_cast<std::int32_t>(k);
  }

  const Adjacency adj(n, intact, broken);
  std::vector<std::int32_t> row;
  for (std::size_t a = 0; a < n; ++a) {
    row.clear();
    const bool a_owned = a < p.n_owned;
    const std::int64_t cx = cell_of(p.pos[a], 0), cy = cell_of(p.pos[a], 1),
                       cz = cell_of(p.pos[a], 2);
    for (std::int64_t z = std::max<std::int64_t>(0, cz - 1); z <= std::min(dims[2] - 1, cz + 1);
         ++z)
      for (std::int64_t y = std::max<std::int64_t>(0, cy - 1); y <= std::min(dims[1] - 1, cy + 1);
           ++y)
        for (std::int64_t x = std::max<std::int64_t>(0, cx - 1); x <= std::min(dims[0] - 1, cx + 1);
             ++x) {
          const std::size_t c = static_cast<std::size_t>((z * dims[1] + y) * dims[0] + x);
          for (std::int32_t m = start[c]; m < start[c + 1]; ++m) {
            const std::int32_t b = members[m];
            if (b <= static_cast<std::int32_t>(a)) continue;
            if (!a_owned && static_cast<std::size_t>(b) >= p.n_owned) continue;  // two ghosts
            const double reach = p.radius[a] + p.radius[b] + skin;
            if ((p.pos[b] - p.pos[a]).squaredNorm() < reach * reach) row.push_back(b);
          }
        }
    std::sort(row.begin(), row.end());
    for (std::int32_t b : row) {
      const auto ia = static_cast<std::int32_t>(a);
      const bool a_first = p.id[a] < p.id[b];
      ContactPair cp{a_first ? ia : b, a_first ? b : ia, adj.lookup(ia, b), Vec3::Zero(),
                     Vec3::Zero()};
      const SpringRecord key{p.id[cp.i], p.id[cp.j], Vec3::Zero(), Vec3::Zero()};
      auto it = std::lower_bound(history.begin(), history.end(), key, id_less);
      if (it != history.end() && it->id_lo == key.id_lo && it->id_hi == key.id_hi) {
        cp.spring = it->spring;
        cp.roll = it->roll;
      }
      pairs.push_back(cp);
    }
  }
}

void NeighbourList::mark_broken(std::int32_t a, std::int32_t b) {
  const std::int32_t lo = std::min(a, b), hi = std::max(a, b);
  auto it = std::lower_bound(
      pairs.begin(), pairs.end(), std::pair{lo, hi}, [](const ContactPair& c, const auto& key) {
        const std::int32_t clo = std::min(c.i, c.j), chi = std::max(c.i, c.j);
        return clo < key.first || (clo == key.first && chi < key.second);
      });
  if (it != pairs.end() && std::min(it->i, it->j) == lo && std::max(it->i, it->j) == hi)
    it->bond = PairBond::broken;
}

void NeighbourList::history_of(const Particles& p, std::int32_t local,
                               std::vector<SpringRecord>& out) const {
  for (const ContactPair& c : pairs)
    if (c.i == local || c.j == local) {
      const SpringRecord r{p.id[c.i], p.id[c.j], c.spring, c.roll};
      if (!r.empty()) out.push_back(r);
    }
}

}  // namespace rockcal
