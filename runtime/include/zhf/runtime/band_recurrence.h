// The band matrices of a rotation by Ivanic & Ruedenberg's recurrence (J. Phys. Chem. 1996, with
// the 1998 errata): band l from band 1 (R on the axes y, z, x) and band l - 1. The one
// implementation: sh::ivanic_ruedenberg (the tests' reference) wraps it, and quarter_turn_bands
// below makes zxzxz's fixed quarter turns X = D(Rx(90 deg)) with it (the emitted kernels' through
// sh::quarter_turn_x, the run-time path's directly), for any order, without a lobe table.
//
// Convention: g_l = D_l f_l for g(w) = f(R^T w), R row-major; band l is (2l+1)^2, row-major, rows
// m' + l, columns m + l. Accuracy: ~1e-15 at order 32 against the independent quadrature
// projection (tests/runtime/every_method_test.cc). Cost: ~10 (2l+1)^2 multiplies per band and a
// few square roots per entry (the coefficients); O(N^3) over the orders.
#pragma once

#include <cmath>
#include <cstdlib>
#include <vector>

#include "zhf/runtime/rotation.h"
#include "zhf/runtime/tolerances.h"

namespace zhf::runtime {

namespace detail {

// A band's entries with m, n in [-l, l].
template <class S>
struct BandRef {
  const S* d;
  int l;
  S operator()(int m, int n) const { return d[(m + l) * (2 * l + 1) + n + l]; }
};

// Their P^l_{i,a,b} (eq. 8.5 with the errata): band 1's row i against band l-1's row a.
template <class S>
S ir_p(int i, int a, int b, int l, const BandRef<S>& r1, const BandRef<S>& prev) {
  if (b == l) return r1(i, 1) * prev(a, l - 1) - r1(i, -1) * prev(a, -l + 1);
  if (b == -l) return r1(i, 1) * prev(a, -l + 1) + r1(i, -1) * prev(a, l - 1);
  return r1(i, 0) * prev(a, b);
}
template <class S>
S ir_v(int m, int n, int l, const BandRef<S>& r1, const BandRef<S>& prev) {
  if (m == 0) return ir_p(1, 1, n, l, r1, prev) + ir_p(-1, -1, n, l, r1, prev);
  if (m > 0) {
    const S d = m == 1 ? 1 : 0;
    return ir_p(1, m - 1, n, l, r1, prev) * std::sqrt(1 + d) - ir_p(-1, -m + 1, n, l, r1, prev) * (1 - d);
  }
  const S d = m == -1 ? 1 : 0;
  return ir_p(1, m + 1, n, l, r1, prev) * (1 - d) + ir_p(-1, -m - 1, n, l, r1, prev) * std::sqrt(1 + d);
}
template <class S>
S ir_w(int m, int n, int l, const BandRef<S>& r1, const BandRef<S>& prev) {
  if (m > 0) return ir_p(1, m + 1, n, l, r1, prev) + ir_p(-1, -m - 1, n, l, r1, prev);
  return ir_p(1, m - 1, n, l, r1, prev) - ir_p(-1, -m + 1, n, l, r1, prev);
}

}  // namespace detail

// bands[l] for l < order, computed in S (long double keeps high orders' quarter turns accurate:
// the recurrence's rounding grows with l).
template <class S = double>
std::vector<std::vector<S>> recurrence_band_matrices(const double r[9], int order) {
  std::vector<std::vector<S>> bands;
  if (order <= 0) return bands;
  bands.push_back({S(1)});
  if (order == 1) return bands;
  std::vector<S> band1(9);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) band1[3 * i + j] = S(r[3 * kBand1Axis[i] + kBand1Axis[j]]);
  bands.push_back(band1);
  const detail::BandRef<S> r1{band1.data(), 1};
  for (int l = 2; l < order; ++l) {
    const int side = 2 * l + 1;
    std::vector<S> band(side * side);
    const detail::BandRef<S> prev{bands[l - 1].data(), l - 1};
    for (int m = -l; m <= l; ++m)
      for (int n = -l; n <= l; ++n) {
        const int am = std::abs(m);
        const S denom = std::abs(n) == l ? S(2 * l) * (2 * l - 1) : S(l + n) * (l - n);
        const S delta_m0 = m == 0 ? 1 : 0;
        const S u = std::sqrt(S(l + m) * (l - m) / denom);
        const S v = S(0.5) * std::sqrt((1 + delta_m0) * S(l + am - 1) * (l + am) / denom) * (1 - 2 * delta_m0);
        const S w = S(-0.5) * std::sqrt(S(l - am - 1) * (l - am) / denom) * (1 - delta_m0);
        S value = 0;
        if (u != 0) value += u * detail::ir_p(0, m, n, l, r1, prev);
        if (v != 0) value += v * detail::ir_v(m, n, l, r1, prev);
        if (w != 0) value += w * detail::ir_w(m, n, l, r1, prev);
        band[(m + l) * side + n + l] = value;
      }
    bands.push_back(std::move(band));
  }
  return bands;
}

// X = D(Rx(+90 deg)) for bands 0..order-1, from Rx's exact entries; the entries that are 0 or +-1
// (half of them are 0) come out exactly so, not as the recurrence's rounding of them.
template <class S = double>
std::vector<std::vector<S>> quarter_turn_bands(int order) {
  const double rx90[9] = {1, 0, 0, 0, 0, -1, 0, 1, 0};
  std::vector<std::vector<S>> bands = recurrence_band_matrices<S>(rx90, order);
  for (std::vector<S>& band : bands)
    for (S& x : band) {
      if (std::abs(x) <= S(tolerance::kExactEntry)) x = 0;
      if (std::abs(std::abs(x) - 1) <= S(tolerance::kExactEntry)) x = x > 0 ? 1 : -1;
    }
  return bands;
}

}  // namespace zhf::runtime
