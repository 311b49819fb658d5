// Random draws that every standard library makes alike. The engine (std::mt19937_64) is specified
// to the bit; the standard library's distribution adaptors are not (libstdc++ and libc++ turn the
// same raw bits into different numbers), so none is used. zhf's outputs (designs, tables, verify inputs,
// the benchmarks' pools) must not change with the standard library, so every draw goes through
// these functions, which use the generator's raw 64-bit output only.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>  // std::mt19937_64 only: its raw output
#include "zhf/sh/random.h"

namespace zhf::sh {

using Rng = std::mt19937_64;

// Uniform double in [0, 1): the top 53 bits of one draw.
inline double uniform01(Rng& rng) { return static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0); }

// Uniform integer in [0, n), n > 0, without modulo bias (rejection).
inline int uniform_index(Rng& rng, int n) {
  constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
  const std::uint64_t limit = kMax - kMax % static_cast<std::uint64_t>(n);
  std::uint64_t x;
  do {
    x = rng();
  } while (x >= limit);
  return static_cast<int>(x % static_cast<std::uint64_t>(n));
}

// Normal draws by Marsaglia's polar method (two uniforms in the unit disc, the second variate
// kept for the next call), scaled to (mean, sigma); called as normal(rng).
template <class T = double>
class Normal {
 public:
  explicit Normal(T mean = 0, T sigma = 1) : mean_(mean), sigma_(sigma) {}

  T operator()(Rng& rng) {
    if (has_spare_) {
      has_spare_ = false;
      return static_cast<T>(mean_ + sigma_ * spare_);
    }
    double u, v, s;
    do {
      u = 2 * uniform01(rng) - 1;
      v = 2 * uniform01(rng) - 1;
      s = u * u + v * v;
    } while (s >= 1 || s == 0);
    const double factor = std::sqrt(-2 * std::log(s) / s);
    spare_ = v * factor;
    has_spare_ = true;
    return static_cast<T>(mean_ + sigma_ * (u * factor));
  }

 private:
  double mean_, sigma_;
  double spare_ = 0;
  bool has_spare_ = false;
};

}  // namespace zhf::sh
