// .spz's quaternion in versions 3 and 4, decoded here as the reference library's README lays it
// out, for the tests that check zhf's files independently.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace zhf::test {

// x y z w from the uint32: the largest component's index in the top 2 bits, then the other three
// in order, 10 bits each (a sign and 9 bits of |q| / sqrt(1/2)); the largest from the unit norm.
inline std::array<double, 4> spz_smallest_three(std::uint32_t word) {
  std::array<double, 4> xyzw{};
  double squares = 0;
  const int largest = int(word >> 30);
  for (int i = 3; i >= 0; --i) {
    if (i == largest) continue;
    xyzw[i] = std::sqrt(0.5) * (word & 511u) / 511 * ((word >> 9) & 1u ? -1 : 1);
    squares += xyzw[i] * xyzw[i];
    word >>= 10;
  }
  xyzw[largest] = std::sqrt(std::max(0.0, 1 - squares));
  return xyzw;
}

}  // namespace zhf::test
