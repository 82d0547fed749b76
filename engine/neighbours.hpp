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
  std::int32_t i,
      j;          // local indices, i the particle with the lower id (same operands on every rank)
  PairBond bond;  // an intact bond excludes the pair from contact forces
  Vec3 spring;    // tangential spring displacement (history), m
  Vec3 roll;      // rolling spring: relative rotation in the tangent plane (history), rad
};

// Tangential and rolling history of one pair, keyed by ids: it survives rebuilds and travels with
// migrating particles.
struct SpringRecord {
  std::int64_t id_lo, id_hi;
  Vec3 spring, roll;
  bool empty() const { return spring.isZero(0.0) && roll.isZero(0.0); }
};

struct NeighbourList {
  std::vector<ContactPair> pairs;  // sorted by (min(i, j), max(i, j))
  std::vector<Vec3> ref_pos;       // owned positions at the last build
  double skin = 0.0;               // m
  std::int64_t builds = 0;

  // Whether an owned particle has moved more than half the skin since the last build.
  bool needs_rebuild(const Particles& p) const;
  // Rebuilds over owned and ghost particles (pairs of two ghosts are left to their owners), keeping
  // the tangential history of persisting pairs and taking `incoming` history from migrants.
  void build(const Particles& p, const std::vector<Bond>& intact, const std::vector<Bond>& broken,
             const std::vector<SpringRecord>& incoming = {});
  // A bond between local particles a and b broke: the pair becomes an ordinary contact.
  void mark_broken(std::int32_t a, std::int32_t b);
  // History of the pairs that involve particle `local` (for migration).
  void history_of(const Particles& p, std::int32_t local, std::vector<SpringRecord>& out) const;

 private:
  std::vector<std::int64_t> p_id_cache_;  // ids of the local particles at the last build
};

}  // namespace rockcal
