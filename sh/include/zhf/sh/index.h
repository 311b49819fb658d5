// Coefficient indexing for real SH in zhf's convention: band l, order m in [-l, l],
// flat index l(l+1)+m; "order N" means bands 0..N-1, i.e. N^2 coefficients.
#pragma once

namespace zhf::sh {

constexpr int kMaxOrder = 64;

constexpr int index(int l, int m) { return l * (l + 1) + m; }
constexpr int coefficient_count(int order) { return order * order; }
constexpr int band_size(int l) { return 2 * l + 1; }
// The band l of coefficient index i = l(l+1)+m.
constexpr int band_of(int i) {
  int l = 0;
  while ((l + 1) * (l + 1) <= i) ++l;
  return l;
}

}  // namespace zhf::sh
