#include "engine/neighbours.hpp"

#include <algorithm>
#include <cmath>

namespace rockcal {
namespace {

// Bond partners of each particle in CSR form, for O(1)-ish lookups during the build.
struct Adjacency {
  std::vector<std::int32_t> offset, partner;
  std::vector<PairBond> state;

  Adjacency(std::size_t n, const std::vector<Bond>& intact, const std::vector<Bond>& broken) {
    offset.assign(n + 1, 0);
    auto count = [&](const std::vector<Bond>& bs) {
      for (const Bond& b : bs) ++offset[b.i + 1];
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
      }
    };
    put(intact, PairBond::intact);
    put(broken, PairBond::broken);
  }

  PairBond lookup(std::int32_t i, std::int32_t j) const {
    for (std::int32_t k = offset[i]; k < offset[i + 1]; ++k)
      if (partner[k] == j) return state[k];
    return PairBond::none;
  }
};

}  // namespace

bool NeighbourList::needs_rebuild(const Particles& p) const {
  if (ref_pos.size() != p.size()) return true;
  const double limit2 = 0.25 * skin * skin;
  for (std::size_t k = 0; k < p.size(); ++k)
    if ((p.pos[k] - ref_pos[k]).squaredNorm() > limit2) return true;
  return false;
}

void NeighbourList::build(const Particles& p, const std::vector<Bond>& intact,
                          const std::vector<Bond>& broken) {
  const std::size_t n = p.size();
  std::vector<ContactPair> old;
  old.swap(pairs);
  ref_pos = p.pos;
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
  std::array<std::int64_t, 3> dims;
  for (int a = 0; a < 3; ++a)
    dims[a] = std::max<std::int64_t>(1, static_cast<std::int64_t>((hi[a] - lo[a]) / cell) + 1);
  auto cell_of = [&](const Vec3& x, int a) {
    return std::min<std::int64_t>(dims[a] - 1, static_cast<std::int64_t>((x[a] - lo[a]) / cell));
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
  std::size_t o = 0;  // cursor into the old (sorted) list, to carry tangential history over
  for (std::size_t i = 0; i < n; ++i) {
    row.clear();
    const std::int64_t cx = cell_of(p.pos[i], 0), cy = cell_of(p.pos[i], 1),
                       cz = cell_of(p.pos[i], 2);
    for (std::int64_t z = std::max<std::int64_t>(0, cz - 1); z <= std::min(dims[2] - 1, cz + 1);
         ++z)
      for (std::int64_t y = std::max<std::int64_t>(0, cy - 1); y <= std::min(dims[1] - 1, cy + 1);
           ++y)
        for (std::int64_t x = std::max<std::int64_t>(0, cx - 1); x <= std::min(dims[0] - 1, cx + 1);
             ++x) {
          const std::size_t c = static_cast<std::size_t>((z * dims[1] + y) * dims[0] + x);
          for (std::int32_t m = start[c]; m < start[c + 1]; ++m) {
            const std::int32_t j = members[m];
            if (j <= static_cast<std::int32_t>(i)) continue;
            const double reach = p.radius[i] + p.radius[j] + skin;
            if ((p.pos[j] - p.pos[i]).squaredNorm() < reach * reach) row.push_back(j);
          }
        }
    std::sort(row.begin(), row.end());
    for (std::int32_t j : row) {
      ContactPair cp{static_cast<std::int32_t>(i), j, adj.lookup(static_cast<std::int32_t>(i), j),
                     Vec3::Zero()};
      while (o < old.size() && (old[o].i < cp.i || (old[o].i == cp.i && old[o].j < cp.j))) ++o;
      if (o < old.size() && old[o].i == cp.i && old[o].j == cp.j) cp.spring = old[o].spring;
      pairs.push_back(cp);
    }
  }
}

void NeighbourList::mark_broken(std::int32_t i, std::int32_t j) {
  if (i > j) std::swap(i, j);
  auto it = std::lower_bound(pairs.begin(), pairs.end(), std::pair{i, j},
                             [](const ContactPair& a, const auto& key) {
                               return a.i < key.first || (a.i == key.first && a.j < key.second);
                             });
  if (it != pairs.end() && it->i == i && it->j == j) it->bond = PairBond::broken;
}

}  // namespace rockcal
