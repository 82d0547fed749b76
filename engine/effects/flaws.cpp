// flaws: bonds cut before loading. Rock holds microcracks and pores that a perfect bonded packing
// lacks; they weaken it more in tension than in compression.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "engine/effects/draw.hpp"
#include "engine/effects/effect.hpp"
#include "engine/simulation.hpp"
#include "engine/spec.hpp"

namespace rockcal {
namespace {

constexpr std::uint64_t kScatterStream = 0x666c617773;  // "flaws"
constexpr std::uint64_t kCrackStream = 0x637261636b;    // "crack"
constexpr std::int64_t kFirstBatch = 16;                // cracks drawn before the first count
// Cracks drawn at most, per bond to cut: a crack smaller than the bond spacing cuts a bond only
// now and then, but a run must end whatever the radius.
constexpr std::int64_t kMaxCracksPerTarget = 64;
constexpr std::int64_t kNotCut = std::numeric_limits<std::int64_t>::max();

// Moves the bonds for which cut(k, bond) holds to the broken list, so that their particles meet as
// broken-bond contacts (post-break friction). No BreakEvent is recorded: a flaw is not a break
// during the test.
template <class Cut>
void cut_bonds(Simulation& sim, Cut cut) {
  std::size_t kept = 0;
  for (std::size_t k = 0; k < sim.bonds.size(); ++k) {
    const Bond b = sim.bonds[k];
    if (cut(k, b)) {
      sim.broken.push_back(b);
      sim.neighbours.mark_broken(b.i, b.j);
    } else {
      sim.bonds[kept++] = b;
    }
  }
  sim.bonds.resize(kept);
}

// A penny-shaped crack: a disc of radius a about `centre`, normal to `normal`.
struct Crack {
  Vec3 centre, normal;
};

// Crack k of the job: centre uniform in the specimen's bounding box, normal uniform on the sphere.
Crack draw_crack(std::uint64_t seed, std::int64_t k, const Vec3& lo, const Vec3& hi) {
  double u[5];
  for (int c = 0; c < 5; ++c)
    u[c] = effects::unit_draw(seed, kCrackStream, static_cast<std::uint64_t>(k),
                              static_cast<std::uint64_t>(c));
  const double z = 2.0 * u[3] - 1.0, phi = 2.0 * M_PI * u[4];
  const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {lo + (hi - lo).cwiseProduct(Vec3(u[0], u[1], u[2])),
          Vec3(s * std::cos(phi), s * std::sin(phi), z)};
}

// Whether the segment x_i -> x_j (a bond) crosses the disc. Every rank evaluates it with the same
// operands (x_i is the lower-id particle, positions are the set-up ones), so all agree.
bool crosses(const Crack& c, double a, const Vec3& x_i, const Vec3& x_j) {
  const double s_i = c.normal.dot(x_i - c.centre), s_j = c.normal.dot(x_j - c.centre);
  if ((s_i > 0 && s_j > 0) || (s_i < 0 && s_j < 0) || s_i == s_j) return false;
  const Vec3 hit = x_i + (s_i / (s_i - s_j)) * (x_j - x_i);
  return (hit - c.centre).squaredNorm() <= a * a;
}

// Bond midpoints binned in cubic cells, so a crack visits only the bonds within its reach.
class MidpointGrid {
 public:
  MidpointGrid(const Simulation& sim, double cell) : cell_(cell) {
    const Particles& p = sim.particles;
    mid_.reserve(sim.bonds.size());
    lo_ = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 hi = -lo_;
    for (const Bond& b : sim.bonds) {
      mid_.push_back(0.5 * (p.pos[b.i] + p.pos[b.j]));
      lo_ = lo_.cwiseMin(mid_.back());
      hi = hi.cwiseMax(mid_.back());
    }
    if (mid_.empty()) return;
    for (int a = 0; a < 3; ++a)
      dims_[a] = std::max<std::int64_t>(1, static_cast<std::int64_t>((hi[a] - lo_[a]) / cell_) + 1);
    start_.assign(static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]) + 1, 0);
    std::vector<std::int64_t> home(mid_.size());
    for (std::size_t k = 0; k < mid_.size(); ++k) ++start_[(home[k] = cell_of(mid_[k])) + 1];
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    members_.resize(mid_.size());
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t k = 0; k < mid_.size(); ++k) members_[fill[home[k]]++] = k;
  }

  // Calls f(bond index) for every bond whose midpoint may lie within `reach` (<= cell) of x.
  template <class F>
  void near(const Vec3& x, F f) const {
    if (mid_.empty()) return;
    std::int64_t from[3], to[3];
    for (int a = 0; a < 3; ++a) {
      from[a] = std::max<std::int64_t>(0, index(x[a] - cell_, a));
      to[a] = std::min<std::int64_t>(dims_[a] - 1, index(x[a] + cell_, a));
      if (from[a] > to[a]) return;
    }
    for (std::int64_t z = from[2]; z <= to[2]; ++z)
      for (std::int64_t y = from[1]; y <= to[1]; ++y)
        for (std::int64_t c = (z * dims_[1] + y) * dims_[0] + from[0],
                          end = (z * dims_[1] + y) * dims_[0] + to[0];
             c <= end; ++c)
          for (std::size_t m = start_[c]; m < start_[c + 1]; ++m) f(members_[m]);
  }

 private:
  std::int64_t index(double x, int a) const {
    const double i = std::floor((x - lo_[a]) / cell_);
    return static_cast<std::int64_t>(std::clamp(i, -1.0, static_cast<double>(dims_[a])));
  }
  std::int64_t cell_of(const Vec3& x) const {
    std::int64_t i[3];
    for (int a = 0; a < 3; ++a) i[a] = std::clamp<std::int64_t>(index(x[a], a), 0, dims_[a] - 1);
    return (i[2] * dims_[1] + i[1]) * dims_[0] + i[0];
  }

  double cell_;
  Vec3 lo_;
  std::int64_t dims_[3] = {1, 1, 1};
  std::vector<Vec3> mid_;
  std::vector<std::size_t> start_, members_;
};

// Cracks are drawn one after another until the bonds they cut reach about `target` (all ranks).
// Each bond belongs to the first crack that crosses it; the per-crack counts are summed over ranks
// in batches, so every rank takes the same number of cracks and cuts the same bonds.
void cut_by_cracks(Simulation& sim, std::uint64_t seed, double a, double target) {
  const Particles& p = sim.particles;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  double longest = 0.0;
  for (std::size_t k = 0; k < p.n_owned; ++k) {
    lo = lo.cwiseMin(p.pos[k]);
    hi = hi.cwiseMax(p.pos[k]);
  }
  for (const Bond& b : sim.bonds) longest = std::max(longest, (p.pos[b.j] - p.pos[b.i]).norm());
  reduce_min(sim.domain, lo.data(), 3);
  reduce_max(sim.domain, hi.data(), 3);
  // A crossed bond's midpoint lies within a + L/2 of the centre.
  const MidpointGrid grid(sim, a + 0.5 * longest);

  std::vector<std::int64_t> first(sim.bonds.size(), kNotCut);
  std::vector<double> counts;  // new cuts per crack, counted by the owner of the lower-id particle
  const auto max_cracks = kMaxCracksPerTarget * static_cast<std::int64_t>(target) + kFirstBatch;
  std::int64_t drawn = 0, batch = kFirstBatch, taken = 0;
  double total = 0.0;
  while (taken == 0) {
    counts.resize(static_cast<std::size_t>(drawn + batch), 0.0);
    for (std::int64_t k = drawn; k < drawn + batch; ++k) {
      const Crack c = draw_crack(seed, k, lo, hi);
      grid.near(c.centre, [&](std::size_t m) {
        const Bond& b = sim.bonds[m];
        if (first[m] != kNotCut || !crosses(c, a, p.pos[b.i], p.pos[b.j])) return;
        first[m] = k;
        if (static_cast<std::size_t>(b.i) < p.n_owned) counts[k] += 1.0;
      });
    }
    reduce_sum(sim.domain, counts.data() + drawn, static_cast<int>(batch));
    for (std::int64_t k = drawn; k < drawn + batch && taken == 0; ++k) {
      const double before = total;
      total += counts[k];
      // Stop at the crack that reaches the target, or the one before if that is closer (but cut
      // at least one crack's worth).
      if (total >= target) taken = (before > 0 && target - before < total - target) ? k : k + 1;
    }
    drawn += batch;
    if (taken == 0 && drawn >= max_cracks) taken = drawn;
    batch *= 2;
  }
  cut_bonds(sim, [&](std::size_t k, const Bond&) { return first[k] < taken; });
}

void cut_flaws(Simulation& sim, const JobSpec& spec, const EffectValues& v) {
  const double fraction = v.at("fraction");
  if (fraction <= 0.0) return;
  const std::uint64_t seed = spec.sample.seed;
  const double a = v.at("crack_radius") * spec.sample.radius_m;
  if (a <= 0.0) {
    // Scattered: each bond on its own, from its global ids.
    cut_bonds(sim, [&](std::size_t, const Bond& b) {
      return effects::unit_draw(seed, kScatterStream, static_cast<std::uint64_t>(b.id_i),
                                static_cast<std::uint64_t>(b.id_j)) < fraction;
    });
    return;
  }
  double owned_bonds = 0.0;
  for (const Bond& b : sim.bonds)
    owned_bonds += static_cast<std::size_t>(b.i) < sim.particles.n_owned ? 1.0 : 0.0;
  const double target = std::round(fraction * sum_over_ranks(sim.domain, owned_bonds));
  if (target >= 1.0) cut_by_cracks(sim, seed, a, target);
}

}  // namespace

EffectDef flaws_effect() {
  EffectDef e;
  e.name = "flaws";
  e.doc =
      "Removes about `fraction` of the bonds before loading. crack_radius = 0: each bond "
      "independently (scattered microcracks); crack_radius > 0 (in particle radii): the bonds "
      "crossed by penny-shaped cracks of that radius, with centres and orientations drawn from "
      "the job seed, until about `fraction` are cut. Cut bonds become broken-bond contacts but do "
      "not count as broken during the test.";
  e.params = {{.name = "fraction",
               .unit = "",
               .lo = 0.0,
               .hi = 0.5,
               .neutral = 0.0,
               .strong = 0.15,
               .log_scale = false,
               .doc = "fraction of the bonds cut before loading"},
              {.name = "crack_radius",
               .unit = "particle radii",
               .lo = 0.0,
               .hi = 20.0,
               .neutral = 0.0,
               .strong = 5.0,
               .log_scale = false,
               .doc = "radius of the penny-shaped cracks; 0 = bonds cut one by one"}};
  e.defaults = {0.05, 0.0};
  e.apply_specimen = cut_flaws;
  e.draws_from_seed = true;
  return e;
}

}  // namespace rockcal
