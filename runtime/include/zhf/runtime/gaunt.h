// Real Gaunt coefficients G_abc = integral over the sphere of y_a y_b y_c, in zhf's convention
// (real orthonormal SH without the Condon-Shortley phase, index l(l+1)+m): the coupling of every
// SH product. h = P_N(f g), the product of two functions projected to order N, is
// h_c = sum_ab G_abc f_a g_b.
//
// Derivation. With the standard complex SH Y_l^m (Condon-Shortley phase), zhf's real SH are
//   y_l^m  = ((-1)^m Y_l^m + Y_l^-m) / sqrt2,           m > 0,
//   y_l^-m = ((-1)^m Y_l^m - Y_l^-m) / (i sqrt2),        m > 0,     y_l^0 = Y_l^0,
// and the complex Gaunt coefficient is the closed form
//   int Y_1 Y_2 Y_3 = sqrt((2l1+1)(2l2+1)(2l3+1) / 4pi) (l1 l2 l3; 0 0 0) (l1 l2 l3; m1 m2 m3)
// with Wigner 3j symbols from Racah's sum. Each real coefficient is the (real) sum of at most
// eight complex ones. Selection rules (checked before any sum): |l1-l2| <= l3 <= l1+l2,
// l1+l2+l3 even, and the |m| satisfy |m3| = |m1| + |m2| or ||m1| - |m2|| in some order, with an
// even count of sine factors (m < 0).
//
// Accuracy: Racah's alternating sum in long double, relative error ~1e-17 times its cancellation,
// within kGauntAgainstQuadrature of a long-double product quadrature up to order 16
// (tests/runtime/gaunt_test.cc). Cost: O(N^6) selection tests and O(N^5) sums to build a table;
// order 16 takes about 0.1 s.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "zhf/runtime/limits.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/runtime/tolerances.h"

namespace zhf::runtime {


namespace gaunt_detail {

inline long double factorial(int n) {
  static const std::vector<long double> table = [] {
    std::vector<long double> t(3 * kMaxGauntOrder + 2, 1.0L);
    for (size_t k = 1; k < t.size(); ++k) t[k] = t[k - 1] * static_cast<long double>(k);
    return t;
  }();
  return table.at(static_cast<size_t>(n));
}

// Wigner 3j (l1 l2 l3; m1 m2 m3) by Racah's formula.
inline long double wigner_3j(int l1, int l2, int l3, int m1, int m2, int m3) {
  if (m1 + m2 + m3 != 0 || l3 < std::abs(l1 - l2) || l3 > l1 + l2) return 0;
  if (std::abs(m1) > l1 || std::abs(m2) > l2 || std::abs(m3) > l3) return 0;
  const int k_min = std::max({0, l2 - l3 - m1, l1 - l3 + m2});
  const int k_max = std::min({l1 + l2 - l3, l1 - m1, l2 + m2});
  long double sum = 0;
  for (int k = k_min; k <= k_max; ++k) {
    const long double term = 1.0L / (factorial(k) * factorial(l3 - l2 + k + m1) * factorial(l3 - l1 + k - m2) *
                                     factorial(l1 + l2 - l3 - k) * factorial(l1 - k - m1) * factorial(l2 - k + m2));
    sum += (k % 2 ? -term : term);
  }
  const long double triangle = factorial(l1 + l2 - l3) * factorial(l1 - l2 + l3) * factorial(-l1 + l2 + l3) /
                               factorial(l1 + l2 + l3 + 1);
  const long double norms = factorial(l1 + m1) * factorial(l1 - m1) * factorial(l2 + m2) * factorial(l2 - m2) *
                            factorial(l3 + m3) * factorial(l3 - m3);
  const int phase = ((l1 - l2 - m3) % 2 + 2) % 2;
  return (phase ? -1.0L : 1.0L) * std::sqrt(triangle * norms) * sum;
}

// The complex SH Y_l^mu in real y_l^m: returns the (at most two) terms (mu, weight).
struct ComplexTerm {
  int mu;
  std::complex<long double> weight;
};
inline int real_to_complex(int m, ComplexTerm out[2]) {
  if (m == 0) {
    out[0] = {0, 1.0L};
    return 1;
  }
  const long double r = 1.0L / std::sqrt(2.0L), sign = (std::abs(m) % 2 ? -1.0L : 1.0L);
  const int a = std::abs(m);
  if (m > 0) {
    out[0] = {a, {sign * r, 0}};
    out[1] = {-a, {r, 0}};
  } else {  // 1 / (i sqrt2) = -i / sqrt2
    out[0] = {a, {0, -sign * r}};
    out[1] = {-a, {0, r}};
  }
  return 2;
}

}  // namespace gaunt_detail

// True when G for these (l, m) may be non-zero: the selection rules above.
inline bool gaunt_allowed(int l1, int m1, int l2, int m2, int l3, int m3) {
  if (l3 < std::abs(l1 - l2) || l3 > l1 + l2 || (l1 + l2 + l3) % 2) return false;
  const int a1 = std::abs(m1), a2 = std::abs(m2), a3 = std::abs(m3);
  if (a3 != a1 + a2 && a3 != std::abs(a1 - a2) && a1 != a2 + a3 && a2 != a1 + a3) return false;
  return ((m1 < 0) + (m2 < 0) + (m3 < 0)) % 2 == 0;
}

// G for flat indices a, b, c (any order; symmetric).
inline double real_gaunt(int a, int b, int c) {
  const int idx[3] = {a, b, c};
  int l[3], m[3];
  for (int k = 0; k < 3; ++k) {
    l[k] = band_of(idx[k]);
    m[k] = idx[k] - l[k] * (l[k] + 1);
  }
  if (!gaunt_allowed(l[0], m[0], l[1], m[1], l[2], m[2])) return 0;
  using gaunt_detail::ComplexTerm;
  ComplexTerm t[3][2];
  int n[3];
  for (int k = 0; k < 3; ++k) n[k] = gaunt_detail::real_to_complex(m[k], t[k]);
  const long double w000 = gaunt_detail::wigner_3j(l[0], l[1], l[2], 0, 0, 0);
  const long double scale = std::sqrt((2.0L * l[0] + 1) * (2.0L * l[1] + 1) * (2.0L * l[2] + 1) / (4 * kPiLong)) * w000;
  std::complex<long double> sum = 0;
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k) {
        if (t[0][i].mu + t[1][j].mu + t[2][k].mu != 0) continue;
        sum += t[0][i].weight * t[1][j].weight * t[2][k].weight *
               gaunt_detail::wigner_3j(l[0], l[1], l[2], t[0][i].mu, t[1][j].mu, t[2][k].mu);
      }
  return static_cast<double>(scale * sum.real());
}

// One non-zero coefficient of a product table: h_c += value (f_a g_b + f_b g_a) for a < b,
// h_c += value f_a g_a for a == b.
struct GauntEntry {
  int c, a, b;
  double value;
};

// Every non-zero G_abc with a <= b and a, b, c below order^2, sorted by (c, a, b): the table of
// h = P_N(f g). Throws std::invalid_argument outside orders 1..kMaxGauntOrder.
inline std::vector<GauntEntry> gaunt_table(int order) {
  if (order < 1 || order > kMaxGauntOrder)
    throw std::invalid_argument("order " + std::to_string(order) + " is outside 1.." + std::to_string(kMaxGauntOrder));
  const int n = order * order;
  std::vector<GauntEntry> table;
  for (int c = 0; c < n; ++c)
    for (int a = 0; a < n; ++a)
      for (int b = a; b < n; ++b) {
        const double g = real_gaunt(a, b, c);
        if (std::abs(g) > tolerance::kGauntZero) table.push_back({c, a, b, g});
      }
  return table;
}

}  // namespace zhf::runtime
