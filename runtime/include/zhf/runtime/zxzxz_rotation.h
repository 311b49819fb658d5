// ZxzxzRotation: the zxzxz factorisation with dense SIMD band products, the run-time path for
// orders where it beats the lobe table (Rotator::from_table picks it by order; docs/performance.md
// gives the measurements). With zyz Euler angles R = Rz(a) Ry(b) Rz(g) and Ry(b) = Rx(-90) Rz(b)
// Rx(+90),
//   D(R) f = Z(a) X- Z(b) X+ Z(g) f,
// where Z(t) turns each (cos m phi, sin m phi) pair by m t and X+ = D(Rx(+90 deg)), X- = X+^T are
// fixed per band, held as DenseRotations (packs of rows, block-diagonal over bands).
//
// Convention as Rotator. Accuracy: the X+ given (from_table: through the lobe path in double,
// ~1e-13 at order 32) and T's rounding over two band products and three turns (float: below 1e-6 on unit inputs
// at order 32, tested); the angles are extracted in double and stable at gimbal lock.
// Cost: 2 sum_l (2l+1) x (packs of rows band l touches) pack multiply-adds, 3 N^2 for the turns,
// three atan2 and one sin/cos pair; no allocation per call.
#pragma once

#include <cmath>
#include <utility>

#include "zhf/runtime/dense_rotation.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/lobe_table.h"
#include "zhf/runtime/table_rotation.h"

namespace zhf::runtime {

// zyz Euler angles of a rotation, stable at and near gimbal lock (b = 0 or pi). a comes from
// R's last column (error ~eps / sin b, which moves the rotation by only ~eps because b's turn
// is that small); g then comes from a + g (upper 2x2 block, well conditioned for cos b >= 0)
// or a - g (for cos b < 0), so the z-turn that dominates near lock is exact to rounding.
template <class T>
void euler_zyz(const T r[9], T& a, T& b, T& g) {
  using std::atan2;
  using std::hypot;
  a = atan2(r[5], r[2]);
  b = atan2(hypot(r[2], r[5]), r[8]);
  if (r[8] >= T(0))
    g = atan2(r[3] - r[1], r[0] + r[4]) - a;     // a + g, from (1 + cos b) (sin, cos)
  else
    g = a - atan2(-(r[3] + r[1]), r[4] - r[0]);  // a - g, from (1 - cos b) (sin, cos)
}

// c[m] = cos(m t), s[m] = sin(m t) for m < order, by the angle-addition recurrence.
template <class T>
void angle_multiples(T t, int order, T* c, T* s) {
  using std::cos;
  using std::sin;
  c[0] = T(1);
  s[0] = T(0);
  if (order < 2) return;
  c[1] = cos(t);
  s[1] = sin(t);
  for (int m = 2; m < order; ++m) {
    c[m] = c[m - 1] * c[1] - s[m - 1] * s[1];
    s[m] = s[m - 1] * c[1] + c[m - 1] * s[1];
  }
}

// Band l (f[m + l]) turned about z by t, given its multiples: g(phi) = f(phi - t) sends the
// (m, -m) weights (x, y) to (x cos mt - y sin mt, x sin mt + y cos mt).
template <class T, class C>
void turn_band(int l, const C* c, const C* s, T* f) {
  for (int m = 1; m <= l; ++m) {
    const T x = f[l + m], y = f[l - m];
    f[l + m] = x * T(c[m]) - y * T(s[m]);
    f[l - m] = x * T(s[m]) + y * T(c[m]);
  }
}

template <class T>
class ZxzxzRotation {
 public:
  ZxzxzRotation() = default;
  // x_plus: D(Rx(+90 deg)) for the order wanted.
  explicit ZxzxzRotation(const DenseRotation<double>& x_plus)
      : order_(x_plus.order()), plus_(convert(x_plus, false)), minus_(convert(x_plus, true)) {}
  // X+ through a lobe table's lobe path in double (the table's shape checked by the caller).
  static ZxzxzRotation from_table(const LobeTable& table) {
    const TableRotation<double> exact(table);
    const double x_plus[9] = {1, 0, 0, 0, 0, -1, 0, 1, 0};
    return ZxzxzRotation(
        dense_rotation<double>(table.order, [&](const double* in, double* out) { exact.rotate(x_plus, in, out, 1); }));
  }

  int order() const { return order_; }

  // out[c N^2 + i] for channels c < channels, from in laid out the same way; in and out must not
  // overlap.
  void rotate(const T r[9], const T* in, T* out, int channels) const {
    double rd[9], a, b, g;
    for (int i = 0; i < 9; ++i) rd[i] = double(r[i]);
    euler_zyz(rd, a, b, g);
    double ca[kMaxTableOrder], sa[kMaxTableOrder], cb[kMaxTableOrder], sb[kMaxTableOrder], cg[kMaxTableOrder],
        sg[kMaxTableOrder];
    angle_multiples(a, order_, ca, sa);
    angle_multiples(b, order_, cb, sb);
    angle_multiples(g, order_, cg, sg);
    const int n = order_ * order_;
    T u[kMaxTableOrder * kMaxTableOrder];
    for (int ch = 0; ch < channels; ++ch) {
      T* o = out + ch * n;
      for (int i = 0; i < n; ++i) o[i] = in[ch * n + i];
      turn_all(cg, sg, o);
      plus_.apply(o, u);
      turn_all(cb, sb, u);
      minus_.apply(u, o);
      turn_all(ca, sa, o);
    }
  }

 private:
  static DenseRotation<T> convert(const DenseRotation<double>& x, bool transposed) {
    std::vector<std::vector<T>> bands;
    for (int l = 0; l < x.order(); ++l) {
      const int size = band_size(l);
      bands.emplace_back(size * size);
      for (int i = 0; i < size; ++i)
        for (int j = 0; j < size; ++j) {
          const double* band = x.bands()[l].data();
          bands[l][i * size + j] = T(transposed ? band[j * size + i] : band[i * size + j]);
        }
    }
    return DenseRotation<T>(x.order(), std::move(bands));
  }
  void turn_all(const double* c, const double* s, T* f) const {
    for (int l = 1; l < order_; ++l) turn_band(l, c, s, f + l * l);
  }

  int order_ = 0;
  DenseRotation<T> plus_{0, {}}, minus_{0, {}};
};

}  // namespace zhf::runtime
