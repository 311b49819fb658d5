// The zxzxz rotation as a reference and for counting operations (the runtime's ZxzxzRotation is
// the fast one, with angles taken from R's entries; this one forms them with atan2): the usual
// fast general method the ZHF paper compares against: with zyz
// Euler angles R = Rz(a) Ry(b) Rz(g) and Ry(b) = Rx(-90) Rz(b) Rx(+90),
//   D(R) f = Z(a) X- Z(b) X+ Z(g) f,
// where Z(t) turns each (cos m phi, sin m phi) pair by m t and X+- = D(Rx(+-90 deg)) are fixed
// per band (computed once from the reference rotation, stored without their zeros).
// Templated on the scalar so float, double and an operation-counting type share one code path.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "zhf/runtime/band_recurrence.h"
#include "zhf/runtime/limits.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"

namespace zhf::sh {

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

// X+ = D(Rx(+90 deg)) for bands 0..order-1 (runtime/band_recurrence.h; its zeros and units exact),
// as Eigen matrices.
inline BandMatrices quarter_turn_x(int order) {
  BandMatrices bands;
  for (const std::vector<double>& band : runtime::quarter_turn_bands(order)) {
    const int side = static_cast<int>(std::lround(std::sqrt(double(band.size()))));
    bands.push_back(Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(band.data(), side, side));
  }
  return bands;
}

template <class T>
class ZxzxzRotator {
 public:

  explicit ZxzxzRotator(int order) : order_(order), plus_(order), minus_(order) {
    if (order < 1 || order > runtime::kMaxShOrder)
      throw std::invalid_argument("ZxzxzRotator: order " + std::to_string(order) + " is outside 1.." + std::to_string(runtime::kMaxShOrder));
    const BandMatrices p = quarter_turn_x(order);
    for (int l = 1; l < order; ++l) {
      plus_[l] = sparse(p[l]);
      minus_[l] = sparse(p[l].transpose());
    }
  }
  int order() const { return order_; }

  // out = coefficients of f(R^T w); R row-major. in and out may not alias.
  void rotate(const T r[9], const T* in, T* out) const { rotate_channels(r, in, out, 1); }

  // Planar channels (in[c * N^2 + i]) under one rotation: the angles and their multiples are
  // computed once.
  void rotate_channels(const T r[9], const T* in, T* out, int channels) const {
    T a, b, g;
    euler_zyz(r, a, b, g);
    Multiples ca, sa, cb, sb, cg, sg;
    angle_multiples(a, order_, ca.data(), sa.data());
    angle_multiples(b, order_, cb.data(), sb.data());
    angle_multiples(g, order_, cg.data(), sg.data());
    Band u, v;
    const int n = order_ * order_;
    for (int c = 0; c < channels; ++c) {
      const T* f = in + c * n;
      T* o = out + c * n;
      o[0] = f[0];
      for (int l = 1; l < order_; ++l) {
        std::copy(f + l * l, f + (l + 1) * (l + 1), u.begin());
        turn_band(l, cg.data(), sg.data(), u.data());
        apply(plus_[l], u, v);
        turn_band(l, cb.data(), sb.data(), v.data());
        apply(minus_[l], v, u);
        turn_band(l, ca.data(), sa.data(), u.data());
        for (int i = 0; i < 2 * l + 1; ++i) o[l * l + i] = u[i];
      }
    }
  }

 private:
  using Multiples = std::array<T, runtime::kMaxShOrder>;  // cos or sin of m t, m = 0..order-1
  using Band = std::array<T, 2 * runtime::kMaxShOrder - 1>;
  struct Entry {
    int row, col;
    double value;
    bool unit;  // +-1: a sign, not a multiply
  };
  // X's entries that are not zero (quarter_turn_x gives its zeros and units exactly), row by row.
  static std::vector<Entry> sparse(const Eigen::MatrixXd& x) {
    std::vector<Entry> out;
    for (int i = 0; i < x.rows(); ++i)
      for (int j = 0; j < x.cols(); ++j)
        if (x(i, j) != 0) out.push_back({i, j, x(i, j), std::abs(x(i, j)) == 1});
    return out;
  }
  // X is orthogonal, so every row has an entry and every output is assigned.
  static void apply(const std::vector<Entry>& x, const Band& in, Band& out) {
    int row = -1;
    for (const Entry& e : x) {
      const T term = e.unit ? (e.value > 0 ? in[e.col] : -in[e.col]) : T(e.value) * in[e.col];
      out[e.row] = e.row == row ? out[e.row] + term : term;
      row = e.row;
    }
  }
  int order_;
  std::vector<std::vector<Entry>> plus_, minus_;  // X+ = D(Rx(+90)), X- = D(Rx(-90)), per band
};

}  // namespace zhf::sh
