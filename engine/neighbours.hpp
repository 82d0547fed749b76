// Candidate pairs for frictional contacts: a cell list with a skin, rebuilt only when some particle
// has moved more than half the skin, so the cost per step stays O(N).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/bonds.hpp"
#include "engine/particles.hpp"

namespace rockcal {

enum class PairBond : std::uint8_t { none, intact, broken };

struct ContactPair {
  std::int32_t i, j;  // i < j
  PairBond bond;      // an intact bond excludes the pair from contact forces
  Vec3 spring;        // tangential spring displacement (history), m
};

struct NeighbourList {
  std::vector<ContactPair> pairs;  // sorted by (i, j)
  std::vector<Vec3> ref_pos;       // positions at the last build
  double skin = 0.0;               // m
  std::int64_t builds = 0;

  bool needs_rebuild(const Particles& p) const;
  // Rebuilds, keeping the tangential history of pairs that persist.
  void build(const Particles& p, const std::vector<Bond>& intact, const std::vector<Bond>& broken);
  // A bond between i and j broke: the pair becomes an ordinary contact from now on.
  void mark_broken(std::int32_t i, std::int32_t j);
};

}  // namespace rockcal
