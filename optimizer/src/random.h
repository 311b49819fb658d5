// Deterministic random helpers. std::uniform_*_distribution are implementation-defined, and
// checked-in tables must not change with the standard library, so draws use raw bits.
#pragma once

#include <cstdint>
#include <limits>
#include <random>

namespace zhf::optimizer::detail {

// Uniform integer in [0, n).
inline int pick(std::mt19937_64& rng, int n) {
  constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
  const std::uint64_t limit = kMax - kMax % static_cast<std::uint64_t>(n);
  std::uint64_t x;
  do {
    x = rng();
  } while (x >= limit);
  return static_cast<int>(x % static_cast<std::uint64_t>(n));
}

// Uniform double in [0, 1).
inline double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0); }

}  // namespace zhf::optimizer::detail
