// Random draws for effects that depend only on (job seed, stream, a, b): every rank that holds the
// same bond (or draws the same crack) gets the same value, so results depend neither on the number
// of ranks nor on the order in which bonds are stored.
#pragma once

#include <cstdint>

namespace rockcal::effects {

// SplitMix64's finaliser: a bijection on 64 bits whose output bits each depend on every input bit.
inline std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// Uniform in the open interval (0, 1): 53 random bits, offset by half a step so neither end occurs
// (an inverse CDF may take the logarithm of u or of 1 - u).
inline double unit_draw(std::uint64_t seed, std::uint64_t stream, std::uint64_t a,
                        std::uint64_t b) {
  const std::uint64_t h = mix64(mix64(mix64(seed ^ mix64(stream)) ^ a) ^ b);
  return (static_cast<double>(h >> 11) + 0.5) * 0x1.0p-53;
}

}  // namespace rockcal::effects
