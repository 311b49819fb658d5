// Real orthonormal SH (no Condon-Shortley phase) at a unit direction.
//
// With z = cos(theta) and C_m + i S_m = (x + i y)^m = sin^m(theta) e^{i m phi}:
//   y_l^0  = Q_l^0(z)
//   y_l^m  = sqrt2 Q_l^m(z) C_m,   y_l^-m = sqrt2 Q_l^m(z) S_m      (m > 0)
// where Q_l^m = K_l^m d^m P_l / dz^m is the normalised associated Legendre function with
// its sin^m factor removed. Q is a polynomial in z (no trig, no division at the poles) and
// its normalised three-term recurrences never form factorials, so they stay finite for
// l < kMaxOrder in float (|Q| < 5e12) and double alike.
#pragma once

#include <cmath>

#include "zhf/sh/index.h"

namespace zhf::sh {

inline constexpr double kInvSqrt4Pi = 0.28209479177387814347;
inline constexpr double kSqrt2 = 1.41421356237309504880;

namespace detail {
// Q_m^m from Q_{m-1}^{m-1}.
inline double diagonal_factor(int m) { return std::sqrt((2.0 * m + 1.0) / (2.0 * m)); }
// Q_{m+1}^m = sqrt(2m+3) z Q_m^m.
inline double subdiagonal_factor(int m) { return std::sqrt(2.0 * m + 3.0); }
// Q_l^m = a (z Q_{l-1}^m - b Q_{l-2}^m).
inline double recurrence_a(int l, int m) {
  return std::sqrt((4.0 * l * l - 1.0) / (double(l) * l - double(m) * m));
}
inline double recurrence_b(int l, int m) {
  const double lm1 = l - 1.0;
  return std::sqrt((lm1 * lm1 - double(m) * m) / (4.0 * lm1 * lm1 - 1.0));
}

// Calls visit(l, m, Q_l^m(z), C_m, S_m) for 0 <= m <= l < order.
template <class T, class Visit>
void for_each_legendre(int order, T x, T y, T z, Visit&& visit) {
  T c = 1, s = 0;
  T q_mm = T(kInvSqrt4Pi);
  for (int m = 0; m < order; ++m) {
    if (m > 0) {
      const T c_next = x * c - y * s;
      s = x * s + y * c;
      c = c_next;
      q_mm *= T(diagonal_factor(m));
    }
    visit(m, m, q_mm, c, s);
    if (m + 1 >= order) continue;
    T q_prev = q_mm;
    T q = T(subdiagonal_factor(m)) * z * q_mm;
    visit(m + 1, m, q, c, s);
    for (int l = m + 2; l < order; ++l) {
      const T q_next = T(recurrence_a(l, m)) * (z * q - T(recurrence_b(l, m)) * q_prev);
      q_prev = q;
      q = q_next;
      visit(l, m, q, c, s);
    }
  }
}
}  // namespace detail

// out[index(l, m)] = y_l^m(dir) for l < order; dir must be unit length.
template <class T>
void eval_sh(int order, const T dir[3], T* out) {
  detail::for_each_legendre<T>(order, dir[0], dir[1], dir[2], [&](int l, int m, T q, T c, T s) {
    if (m == 0) {
      out[index(l, 0)] = q;
    } else {
      out[index(l, m)] = T(kSqrt2) * q * c;
      out[index(l, -m)] = T(kSqrt2) * q * s;
    }
  });
}

// out[m + l] = y_l^m(dir) for the single band l.
template <class T>
void eval_band(int l, const T dir[3], T* out) {
  detail::for_each_legendre<T>(l + 1, dir[0], dir[1], dir[2], [&](int band, int m, T q, T c, T s) {
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

}  // namespace zhf::sh
