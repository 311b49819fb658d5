// Real orthonormal SH (no Condon-Shortley phase) at a unit direction: zhf's one implementation
// of the Legendre recurrence. Everything else calls it (the runtime's table path, the reference
// math, Legendre roots) or is generated from its coefficients (the emitted kernels).
//
// With z = cos(theta) and C_m + i S_m = (x + i y)^m = sin^m(theta) e^{i m phi}:
//   y_l^0  = Q_l^0(z)
//   y_l^m  = sqrt2 Q_l^m(z) C_m,   y_l^-m = sqrt2 Q_l^m(z) S_m      (m > 0)
// where Q_l^m = K_l^m d^m P_l / dz^m is the normalised associated Legendre function with its
// sin^m factor removed:
//   Q_0^0 = 1/sqrt(4 pi),   Q_m^m = diagonal(m) Q_{m-1}^{m-1},   Q_{m+1}^m = subdiagonal(m) z Q_m^m,
//   Q_l^m = a(l, m) (z Q_{l-1}^m - b(l, m) Q_{l-2}^m).
// Its rounding is part of zhf's outputs (searched tables, designs): change the form and those change.
// Q is a polynomial in z (no trig, no division at the poles), and the normalised recurrences never
// form factorials, so they stay finite below order kMaxShOrder in float and double alike.
// Accuracy: a few ulps per step; measured 1.6e-13 relative at order 64 in double.
// Cost: O(N^2) per direction for all bands; tabulated coefficients save the square roots.
#pragma once

#include <cmath>
#include <vector>

namespace zhf::runtime {

inline constexpr double kInvSqrt4Pi = 0.28209479177387814347;  // y_0^0
inline constexpr double kSqrt2 = 1.41421356237309504880;
inline constexpr double kPi = 3.14159265358979323846;
inline constexpr long double kPiLong = 3.141592653589793238462643383279502884L;  // the long-double references

// Coefficient indexing: band l, m in [-l, l], flat index l(l+1)+m.
constexpr int index(int l, int m) { return l * (l + 1) + m; }
constexpr int coefficient_count(int order) { return order * order; }
constexpr int band_size(int l) { return 2 * l + 1; }
// The band of flat index i.
constexpr int band_of(int i) {
  int l = 0;
  while ((l + 1) * (l + 1) <= i) ++l;
  return l;
}

// The recurrence's coefficients, computed in R.
template <class R = double>
struct LegendreCoefficients {
  static R diagonal(int m) { return std::sqrt((R(2) * m + R(1)) / (R(2) * m)); }
  static R subdiagonal(int m) { return std::sqrt(R(2) * m + R(3)); }
  static R a(int l, int m) { return std::sqrt((R(4) * l * l - R(1)) / (R(l) * l - R(m) * m)); }
  static R b(int l, int m) {
    const R lm1 = R(l) - R(1);
    return std::sqrt((lm1 * lm1 - R(m) * m) / (R(4) * lm1 * lm1 - R(1)));
  }
};

// The same, tabulated once for orders below `order` (the run-time paths evaluate many directions).
class TabulatedLegendreCoefficients {
 public:
  explicit TabulatedLegendreCoefficients(int order)
      : order_(order), diagonal_(order), subdiagonal_(order), a_(order * order), b_(order * order) {
    using K = LegendreCoefficients<>;
    for (int m = 0; m < order; ++m) {
      if (m > 0) diagonal_[m] = K::diagonal(m);
      subdiagonal_[m] = K::subdiagonal(m);
    }
    for (int l = 2; l < order; ++l)
      for (int m = 0; m + 2 <= l; ++m) {
        a_[l * order + m] = K::a(l, m);
        b_[l * order + m] = K::b(l, m);
      }
  }
  int order() const { return order_; }
  double diagonal(int m) const { return diagonal_[m]; }
  double subdiagonal(int m) const { return subdiagonal_[m]; }
  double a(int l, int m) const { return a_[l * order_ + m]; }
  double b(int l, int m) const { return b_[l * order_ + m]; }

 private:
  int order_;
  std::vector<double> diagonal_, subdiagonal_, a_, b_;
};

// Calls visit(l, Q_l^m(z)) for l = m..top, starting from q_mm = Q_m^m: the recurrence in l.
template <class T, class Coefficients, class Visit>
void legendre_column(int m, int top, const T& z, const T& q_mm, const Coefficients& k, Visit&& visit) {
  visit(m, q_mm);
  if (m + 1 > top) return;
  T q_prev = q_mm;
  T q = T(k.subdiagonal(m)) * z * q_mm;
  visit(m + 1, q);
  for (int l = m + 2; l <= top; ++l) {
    const T next = T(k.a(l, m)) * (z * q - T(k.b(l, m)) * q_prev);
    q_prev = q;
    q = next;
    visit(l, q);
  }
}

// Calls visit(l, m, Q_l^m(z), C_m, S_m) for 0 <= m <= l < order, at the unit direction (x, y, z).
template <class T, class Coefficients, class Visit>
void for_each_legendre(int order, const T& x, const T& y, const T& z, const Coefficients& k, Visit&& visit) {
  T c = 1, s = 0;
  T q_mm = T(kInvSqrt4Pi);
  for (int m = 0; m < order; ++m) {
    if (m > 0) {
      const T c_next = x * c - y * s;
      s = x * s + y * c;
      c = c_next;
      q_mm *= T(k.diagonal(m));
    }
    legendre_column(m, order - 1, z, q_mm, k, [&](int l, const T& q) { visit(l, m, q, c, s); });
  }
}

// Q_l^m(z) alone, O(l) (Legendre roots, quadrature nodes).
template <class T>
T legendre_q(int l, int m, T z) {
  if (m < 0 || m > l) return T(0);
  using K = LegendreCoefficients<T>;
  T q_mm = T(kInvSqrt4Pi);
  for (int k = 1; k <= m; ++k) q_mm *= K::diagonal(k);
  T out = 0;
  legendre_column(m, l, z, q_mm, K{}, [&](int band, T q) {
    if (band == l) out = q;
  });
  return out;
}

// out[index(l, m)] = y_l^m(dir) for l < order; dir must be unit length.
template <class T, class Coefficients = LegendreCoefficients<>>
void eval_sh(int order, const T dir[3], T* out, const Coefficients& k = {}) {
  for_each_legendre<T>(order, dir[0], dir[1], dir[2], k, [&](int l, int m, T q, T c, T s) {
    if (m == 0) {
      out[index(l, 0)] = q;
    } else {
      out[index(l, m)] = T(kSqrt2) * q * c;
      out[index(l, -m)] = T(kSqrt2) * q * s;
    }
  });
}

// out[m + l] = y_l^m(dir) for the single band l.
template <class T, class Coefficients = LegendreCoefficients<>>
void eval_band(int l, const T dir[3], T* out, const Coefficients& k = {}) {
  for_each_legendre<T>(l + 1, dir[0], dir[1], dir[2], k, [&](int band, int m, T q, T c, T s) {
    if (band != l) return;
    if (m == 0) {
      out[l] = q;
    } else {
      out[l + m] = T(kSqrt2) * q * c;
      out[l - m] = T(kSqrt2) * q * s;
    }
  });
}

// Unit direction from spherical angles: theta from +z, phi from +x towards +y.
template <class T>
void direction_from_angles(T theta, T phi, T dir[3]) {
  dir[0] = std::sin(theta) * std::cos(phi);
  dir[1] = std::sin(theta) * std::sin(phi);
  dir[2] = std::cos(theta);
}

}  // namespace zhf::runtime
