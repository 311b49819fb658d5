// SH products and their integrals, with terms in SH or in zhf's zonal form (ZHF: the rotated
// zonal-harmonic basis, RZHB).
//
// Conventions: coefficients in zhf's real SH; a term in ZHF form is the lobe-weight vector z with
// f = Y^T z, where Y is block diagonal: band l >= 2 holds Y_l[d][m+l] = y_l^m(w_{l,d}) for the
// table's lobes, bands 0 and 1 stay SH coefficients (identity blocks), exactly the layout of the
// emitted lobe_weights kernels (z = A^T f). A rotated term (lobes at R w_d) uses Y_R, whose
// band-1 block is the transposed band-1 rotation, so that Y_R^T z is the rotated function.
//
// Derivations (each beside the code that implements it below):
//   double product, both SH:    int f g = f . g                     (orthonormality: coupling I)
//   one term in ZHF form:       int (Y^T z) g = z . (Y g)            (coupling C^D = Y)
//   both in ZHF form:           int (Y1^T z1)(Y2^T z2) = z1 . (Y1 Y2^T) z2   (coupling Y1 Y2^T)
//   triple product, SH:         int f g h = sum G_abc f_a g_b h_c    (G: runtime/gaunt.h)
//   with k terms in ZHF form:   T = G contracted with Y on those k slots, T_dbc = sum_a Y_da G_abc
//                               (one slot), stored once like C^D: int = sum T_ijk x_i y_j w_k
//   product projected to order N: h = P_N(f g), h_c = sum_ab G_abc f_a g_b.
// Either Y may be a Y_R in every line. Accuracy: double rounding of sums of at most N^4 terms
// (within kProductAgainstIntegration of numerical integration, tests/runtime/product_test.cc);
// in float within kFloatProduct.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <vector>

#include "zhf/runtime/gaunt.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/lobe_table.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/sh_eval.h"

namespace zhf::runtime {

// h = P_N(f g) and the triple-product integral, for SH terms of one order.
// Cost: the table's entries (N = 8: 6588) per call, two multiplies each; building: gaunt_table.
class ShProduct {
 public:
  explicit ShProduct(int order) : order_(order), table_(gaunt_table(order)) {}
  int order() const { return order_; }
  const std::vector<GauntEntry>& table() const { return table_; }

  // h[0..N^2) = P_N(f g); h may not alias f or g.
  template <class T>
  void product(const T* f, const T* g, T* h) const {
    for (int c = 0; c < order_ * order_; ++c) h[c] = T(0);
    for (const GauntEntry& e : table_)
      h[e.c] += T(e.value) * (e.a == e.b ? f[e.a] * g[e.a] : f[e.a] * g[e.b] + f[e.b] * g[e.a]);
  }
  template <class T>
  void square(const T* f, T* h) const {
    product(f, f, h);
  }
  // int f g h over the sphere.
  template <class T>
  T triple(const T* f, const T* g, const T* h) const {
    T sum = T(0);
    for (const GauntEntry& e : table_)
      sum += T(e.value) * h[e.c] * (e.a == e.b ? f[e.a] * g[e.a] : f[e.a] * g[e.b] + f[e.b] * g[e.a]);
    return sum;
  }

 private:
  int order_;
  std::vector<GauntEntry> table_;
};

// The ZHF form of one order: Y (or Y_R) as a block-diagonal matrix. Order 2 needs no table.
class ZhfBasis {
 public:
  // Y from the table's lobes. Throws InputError for a table of the wrong shape.
  explicit ZhfBasis(const LobeTable& table) : ZhfBasis(table, kIdentity.data()) {}
  // Y_R: the lobes rotated by R (row-major, a rotation).
  ZhfBasis(const LobeTable& table, const double r[9]) : order_(table.order), n_(table.order * table.order), y_(n_, n_) {
    validate_lobe_table(table, "ZhfBasis", TableCheck::kShape);
    y_(0, 0) = 1;
    if (order_ > 1) {
      // Band 1: f' = M1 f, so the block of Y_R (f' = Y_R^T z) is M1^T.
      for (int j = 0; j < 3; ++j) {
        double e[3] = {0, 0, 0}, col[3];
        e[j] = 1;
        rotate_band1(r, e, col);
        for (int i = 0; i < 3; ++i) y_(1 + j, 1 + i) = col[i];
      }
    }
    for (const TableBand& band : table.bands) {
      const int b0 = band.l * band.l, size = 2 * band.l + 1;
      std::vector<double> y(size);
      for (int d = 0; d < size; ++d) {
        const auto& w = table.lobes[band.lobes[d]].xyz;
        const double rw[3] = {r[0] * w[0] + r[1] * w[1] + r[2] * w[2], r[3] * w[0] + r[4] * w[1] + r[5] * w[2],
                              r[6] * w[0] + r[7] * w[1] + r[8] * w[2]};
        eval_band(band.l, rw, y.data());
        for (int m = 0; m < size; ++m) y_(b0 + d, b0 + m) = y[m];
      }
    }
  }

  int order() const { return order_; }
  // Y[i][j], i a lobe (or band 0/1 coefficient), j an SH coefficient.
  double operator()(int i, int j) const { return y_(i, j); }

  // f = Y^T z: the function a ZHF-form term stands for.
  template <class T>
  void to_sh(const T* z, T* f) const {
    for (int j = 0; j < n_; ++j) {
      T sum = T(0);
      for (int i = block_begin(j); i < block_end(j); ++i) sum += T(y_(i, j)) * z[i];
      f[j] = sum;
    }
  }
  // out = Y g: the coupling C^D = Y applied to an SH term (int (Y^T z) g = z . out).
  template <class T>
  void couple(const T* g, T* out) const {
    for (int i = 0; i < n_; ++i) {
      T sum = T(0);
      for (int j = block_begin(i); j < block_end(i); ++j) sum += T(y_(i, j)) * g[j];
      out[i] = sum;
    }
  }

 private:
  // Y is block diagonal by band: the range of the band holding index k.
  static int block_begin(int k) { return band_of(k) * band_of(k); }
  static int block_end(int k) { return (band_of(k) + 1) * (band_of(k) + 1); }

  int order_, n_;
  Matrix y_;
};

// Every basis given must be of the order the product is formed at.
inline void check_bases(int order, std::initializer_list<const ZhfBasis*> bases, const char* who) {
  for (const ZhfBasis* b : bases)
    if (b && b->order() != order)
      throw std::invalid_argument(std::string(who) + ": a basis of order " + std::to_string(b->order()) + " in a product of order " +
                                  std::to_string(order));
}

// One term of a product integral: SH coefficients (basis null) or a ZHF-form vector z with the
// basis (Y or Y_R) it is expressed in.
template <class T>
struct ProductTerm {
  const T* values = nullptr;
  const ZhfBasis* basis = nullptr;
};

// The coupling of a double-product integral: I (both SH), Y (C^D, one ZHF term) or Y1 Y2^T (both):
// int f g = x^T C y. Order N, N^2 x N^2.
inline Matrix double_coupling(int order, const ZhfBasis* first, const ZhfBasis* second) {
  check_bases(order, {first, second}, "double_coupling");
  const int n = order * order;
  Matrix c(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double sum = 0;  // (Y1 Y2^T)_ij = sum_k Y1_ik Y2_jk, with I for an SH slot
      for (int k = 0; k < n; ++k)
        sum += (first ? (*first)(i, k) : double(i == k)) * (second ? (*second)(j, k) : double(j == k));
      c(i, j) = sum;
    }
  return c;
}


// The coupling tensor T of int f g h with each slot in SH (null) or ZHF form: T_ijk, stored
// dense in i-major order. Built from G by contracting Y into each ZHF slot.
inline std::vector<double> triple_coupling(int order, const ZhfBasis* slots[3]) {
  if (order < 1 || order > kMaxTripleCouplingOrder)
    throw std::invalid_argument("triple_coupling: order " + std::to_string(order) + " is outside 1.." +
                                std::to_string(kMaxTripleCouplingOrder));
  check_bases(order, {slots[0], slots[1], slots[2]}, "triple_coupling");
  const std::size_t n = std::size_t(order) * order;
  std::vector<double> t(n * n * n, 0.0);
  for (const GauntEntry& e : gaunt_table(order)) {
    const int perms[6][3] = {{e.a, e.b, e.c}, {e.a, e.c, e.b}, {e.b, e.a, e.c}, {e.b, e.c, e.a}, {e.c, e.a, e.b}, {e.c, e.b, e.a}};
    // G is symmetric: write every distinct permutation of the entry once.
    for (int p = 0; p < 6; ++p) t[(perms[p][0] * n + perms[p][1]) * n + perms[p][2]] = e.value;
  }
  for (int slot = 0; slot < 3; ++slot) {
    if (!slots[slot]) continue;
    std::vector<double> next(t.size(), 0.0);
    const std::size_t stride[3] = {n * n, n, 1};
    for (std::size_t flat = 0; flat < t.size(); ++flat) {
      if (t[flat] == 0) continue;
      const int a = static_cast<int>(flat / stride[slot] % n);
      const int b0 = band_of(a) * band_of(a), b1 = (band_of(a) + 1) * (band_of(a) + 1);
      for (int d = b0; d < b1; ++d) next[flat + (std::size_t(d) - a) * stride[slot]] += (*slots[slot])(d, a) * t[flat];
    }
    t.swap(next);
  }
  return t;
}

// int f g over the sphere, each term in SH or ZHF form (of one order).
template <class T>
T double_product(int order, ProductTerm<T> f, ProductTerm<T> g) {
  check_bases(order, {f.basis, g.basis}, "double_product");
  const int n = order * order;
  std::vector<T> fs(f.values, f.values + n), gs(g.values, g.values + n);
  if (f.basis && g.basis) {  // z1 . (Y1 Y2^T) z2 = (Y1^T z1) . (Y2^T z2)
    f.basis->to_sh(f.values, fs.data());
    g.basis->to_sh(g.values, gs.data());
  } else if (f.basis) {  // z . (Y g)
    f.basis->couple(g.values, gs.data());
  } else if (g.basis) {
    g.basis->couple(f.values, fs.data());
  }
  T sum = T(0);
  for (int i = 0; i < n; ++i) sum += fs[i] * gs[i];
  return sum;
}

// int f g h over the sphere, each term in SH or ZHF form: the ZHF terms go to SH through Y^T
// (cheaper per call than the stored coupling tensor, equal to it: tests compare both).
template <class T>
T triple_product(const ShProduct& product, ProductTerm<T> f, ProductTerm<T> g, ProductTerm<T> h) {
  check_bases(product.order(), {f.basis, g.basis, h.basis}, "triple_product");
  const int n = product.order() * product.order();
  std::vector<T> sh[3];
  const ProductTerm<T>* terms[3] = {&f, &g, &h};
  for (int k = 0; k < 3; ++k) {
    sh[k].assign(terms[k]->values, terms[k]->values + n);
    if (terms[k]->basis) terms[k]->basis->to_sh(terms[k]->values, sh[k].data());
  }
  return product.triple(sh[0].data(), sh[1].data(), sh[2].data());
}

}  // namespace zhf::runtime
