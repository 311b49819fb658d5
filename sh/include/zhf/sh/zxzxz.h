// The zxzxz rotation, the usual fast general method the ZHF paper compares against: with zyz
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

template <class T>
class ZxzxzRotator {
 public:

  explicit ZxzxzRotator(int order) : order_(order), plus_(order), minus_(order) {
    if (order < 1 || order > runtime::kMaxShOrder)
      throw std::invalid_argument("ZxzxzRotator: order " + std::to_string(order) + " is outside 1.." + std::to_string(runtime::kMaxShOrder));
    const double half_pi = 1.57079632679489661923;
    const BandMatrices p = ivanic_ruedenberg(rotation_about_axis(Eigen::Vector3d::UnitX(), half_pi), order);
    const BandMatrices m = ivanic_ruedenberg(rotation_about_axis(Eigen::Vector3d::UnitX(), -half_pi), order);
    for (int l = 1; l < order; ++l) {
      plus_[l] = sparse(p[l]);
      minus_[l] = sparse(m[l]);
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
    multiples(a, ca, sa);
    multiples(b, cb, sb);
    multiples(g, cg, sg);
    Band u, v;
    const int n = order_ * order_;
    for (int c = 0; c < channels; ++c) {
      const T* f = in + c * n;
      T* o = out + c * n;
      o[0] = f[0];
      for (int l = 1; l < order_; ++l) {
        std::copy(f + l * l, f + (l + 1) * (l + 1), u.begin());
        turn(l, cg, sg, u);
        apply(plus_[l], u, v);
        turn(l, cb, sb, v);
        apply(minus_[l], v, u);
        turn(l, ca, sa, u);
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
  // X's entries that are not zero (|x| < 1e-14: exact zeros up to the reference's rounding),
  // row by row.
  static std::vector<Entry> sparse(const Eigen::MatrixXd& x) {
    std::vector<Entry> out;
    for (int i = 0; i < x.rows(); ++i)
      for (int j = 0; j < x.cols(); ++j) {
        if (std::abs(x(i, j)) <= 1e-14) continue;
        const bool unit = std::abs(std::abs(x(i, j)) - 1) <= 1e-14;
        out.push_back({i, j, unit ? (x(i, j) > 0 ? 1.0 : -1.0) : x(i, j), unit});
      }
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
  // cos(m t), sin(m t) for m = 0..order-1 by the angle-addition recurrence.
  void multiples(T t, Multiples& c, Multiples& s) const {
    using std::cos;
    using std::sin;
    c[0] = T(1);
    s[0] = T(0);
    if (order_ < 2) return;
    c[1] = cos(t);
    s[1] = sin(t);
    for (int m = 2; m < order_; ++m) {
      c[m] = c[m - 1] * c[1] - s[m - 1] * s[1];
      s[m] = s[m - 1] * c[1] + c[m - 1] * s[1];
    }
  }
  // Rotation about z by t: g(phi) = f(phi - t) sends the (m, -m) weights (a, b) to
  // (a cos mt - b sin mt, a sin mt + b cos mt).
  static void turn(int l, const Multiples& c, const Multiples& s, Band& f) {
    for (int m = 1; m <= l; ++m) {
      const T x = f[l + m], y = f[l - m];
      f[l + m] = x * c[m] - y * s[m];
      f[l - m] = x * s[m] + y * c[m];
    }
  }

  int order_;
  std::vector<std::vector<Entry>> plus_, minus_;  // X+ = D(Rx(+90)), X- = D(Rx(-90)), per band
};

}  // namespace zhf::sh
