// 3x3 rotations in zhf's convention: R is row-major and maps a direction v to R v; rotating an
// SH function f by R gives g(w) = f(R^T w). The checks, repairs and small constructions every
// rotation path shares.
//
// Policy: the rotators rotate by proper rotations only. validate_rotation() reports the measured
// defect; debug builds assert it; nearest_rotation() (polar decomposition) is the explicit way to
// accept a matrix that is off by rounding. Reflections (det -1) are what orthogonal.h is for: a
// caller that means one asks validate_rotation for Handedness::kEither and transforms through it.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

#include "zhf/runtime/errors.h"
#include "zhf/runtime/tolerances.h"

namespace zhf::runtime {

// Band 1 is c (y, z, x): element m + 1 of band 1 is axis kBand1Axis[m + 1], so band 1 rotates by
// R restricted to those axes.
inline constexpr int kBand1Axis[3] = {1, 2, 0};

// out = band 1 of the coefficients of f(R^T w), from band 1 of f (in and out: 3 entries each).
template <class T, class R>
inline void rotate_band1(const R r[9], const T in[3], T out[3]) {
  for (int i = 0; i < 3; ++i) {
    T sum = 0;
    for (int j = 0; j < 3; ++j) sum += T(r[3 * kBand1Axis[i] + kBand1Axis[j]]) * in[j];
    out[i] = sum;
  }
}

struct RotationCheck {
  bool ok = false;
  bool finite = false;
  double orthonormality = 0;  // max |R R^T - I|
  double determinant = 0;
  std::string message;        // empty when ok
};

// det r, r row-major 3x3, in double.
template <class T>
double determinant(const T r[9]) {
  const double m[9] = {double(r[0]), double(r[1]), double(r[2]), double(r[3]), double(r[4]),
                       double(r[5]), double(r[6]), double(r[7]), double(r[8])};
  return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
}

// Which determinant is accepted: +1 only (the rotators), or -1 too (orthogonal.h).
enum class Handedness { kProper, kEither };

template <class T>
RotationCheck validate_rotation(const T r[9], double max_defect = tolerance::kRotationDefect,
                                Handedness handedness = Handedness::kProper) {
  RotationCheck check;
  check.finite = true;
  for (int i = 0; i < 9; ++i) check.finite = check.finite && std::isfinite(static_cast<double>(r[i]));
  if (!check.finite) {
    check.message = "rotation matrix has a non-finite entry";
    return check;
  }
  double m[9];
  for (int i = 0; i < 9; ++i) m[i] = r[i];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double dot = 0;
      for (int k = 0; k < 3; ++k) dot += m[3 * i + k] * m[3 * j + k];
      check.orthonormality = std::max(check.orthonormality, std::abs(dot - (i == j ? 1.0 : 0.0)));
    }
  check.determinant = determinant(r);
  if (check.determinant < 0 && handedness == Handedness::kProper) {
    check.message = "rotation matrix is a reflection (det " + format_number(check.determinant) + ")";
  } else if (check.orthonormality > max_defect || std::abs(std::abs(check.determinant) - 1) > max_defect) {
    check.message = "rotation matrix is not orthonormal: max |R R^T - I| = " + format_number(check.orthonormality) +
                    ", det = " + format_number(check.determinant) + " (tolerance " +
                    format_number(max_defect) + ")";
  } else {
    check.ok = true;
  }
  return check;
}

// Whether validate_rotation(r, max_defect, handedness) accepts r: the same arithmetic on the six
// distinct entries of R R^T and the determinant, without the measures' record or a message, for
// checking many matrices (about half validate_rotation's cost). A non-finite entry fails every
// comparison, so it is refused too.
template <class T>
bool rotation_accepted(const T r[9], double max_defect = tolerance::kRotationDefect,
                       Handedness handedness = Handedness::kProper) {
  double m[9];
  for (int i = 0; i < 9; ++i) m[i] = r[i];
  bool ok = true;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      double dot = 0;
      for (int k = 0; k < 3; ++k) dot += m[3 * i + k] * m[3 * j + k];
      ok &= std::abs(dot - (i == j ? 1.0 : 0.0)) <= max_defect;
    }
  const double det = determinant(r);
  ok &= std::abs(std::abs(det) - 1) <= max_defect;
  if (handedness == Handedness::kProper) ok &= det > 0;
  return ok;
}

// Nearest proper rotation to r (Frobenius), by the Newton iteration for the polar factor
// X <- (X + X^-T) / 2, which converges quadratically from any nonsingular start. Accuracy: a few
// ulps of double. Returns false (and leaves out untouched) for singular, non-finite or
// reflecting input.
template <class T>
bool nearest_rotation(const T r[9], T out[9]) {
  double x[9];
  for (int i = 0; i < 9; ++i) {
    x[i] = r[i];
    if (!std::isfinite(x[i])) return false;
  }
  for (int it = 0; it < 100; ++it) {
    const double c[9] = {x[4] * x[8] - x[5] * x[7], x[5] * x[6] - x[3] * x[8], x[3] * x[7] - x[4] * x[6],
                         x[2] * x[7] - x[1] * x[8], x[0] * x[8] - x[2] * x[6], x[1] * x[6] - x[0] * x[7],
                         x[1] * x[5] - x[2] * x[4], x[2] * x[3] - x[0] * x[5], x[0] * x[4] - x[1] * x[3]};
    const double det = x[0] * c[0] + x[1] * c[1] + x[2] * c[2];
    if (!(std::abs(det) > tolerance::kSingularDeterminant) || !std::isfinite(det)) return false;
    // X^-T = cofactor matrix / det.
    double change = 0;
    for (int i = 0; i < 9; ++i) {
      const double next = 0.5 * (x[i] + c[i] / det);
      change = std::max(change, std::abs(next - x[i]));
      x[i] = next;
    }
    if (change < tolerance::kPolarStep) break;
  }
  const double det = x[0] * (x[4] * x[8] - x[5] * x[7]) - x[1] * (x[3] * x[8] - x[5] * x[6]) +
                     x[2] * (x[3] * x[7] - x[4] * x[6]);
  if (det < 0) return false;
  for (int i = 0; i < 9; ++i) out[i] = static_cast<T>(x[i]);
  return true;
}

// nearest_rotation for either handedness: a reflection Q is -(-Q), with -Q a rotation.
template <class T>
bool nearest_orthogonal(const T r[9], T out[9]) {
  if (!(determinant(r) < 0)) return nearest_rotation(r, out);
  T negated[9];
  for (int i = 0; i < 9; ++i) negated[i] = -r[i];
  if (!nearest_rotation(negated, out)) return false;
  for (int i = 0; i < 9; ++i) out[i] = -out[i];
  return true;
}

// One Newton step toward a nearly orthonormal R's polar factor, Q = R (3 I - R^T R) / 2, in a
// wider type W. A float R is orthonormal to eps_f only, and a lobe fit amplifies its symmetric
// part by the band's condition number; after the step what remains is O(eps_f^2). The emitted
// kernels whose lobe stage runs in double do the same step.
template <class W, class T>
inline void polar_step(const T r[9], W q[9]) {
  W step[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      W gram = 0;
      for (int k = 0; k < 3; ++k) gram += W(r[3 * k + i]) * W(r[3 * k + j]);
      step[3 * i + j] = (i == j ? W(1.5) : W(0)) - W(0.5) * gram;
    }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      W sum = 0;
      for (int k = 0; k < 3; ++k) sum += W(r[3 * i + k]) * step[3 * k + j];
      q[3 * i + j] = sum;
    }
}

using Matrix3 = std::array<double, 9>;
inline constexpr Matrix3 kIdentity{1, 0, 0, 0, 1, 0, 0, 0, 1};

// a b, row-major.
inline Matrix3 multiply(const Matrix3& a, const Matrix3& b) {
  Matrix3 out{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) out[3 * i + j] += a[3 * i + k] * b[3 * k + j];
  return out;
}

inline Matrix3 transpose(const Matrix3& a) { return {a[0], a[3], a[6], a[1], a[4], a[7], a[2], a[5], a[8]}; }

// A right-handed turn by angle (radians) about the unit axis u (Rodrigues).
inline Matrix3 rotation_about_unit_axis(const double u[3], double angle) {
  const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;
  return {t * u[0] * u[0] + c,        t * u[0] * u[1] - s * u[2], t * u[0] * u[2] + s * u[1],
          t * u[0] * u[1] + s * u[2], t * u[1] * u[1] + c,        t * u[1] * u[2] - s * u[0],
          t * u[0] * u[2] - s * u[1], t * u[1] * u[2] + s * u[0], t * u[2] * u[2] + c};
}

// The rotation of the quaternion q = w + x i + y j + z k, of any nonzero length (it is divided by
// |q|): v -> q v q*, a right-handed turn by 2 acos(w / |q|) about (x, y, z); q and -q give the
// same R. Returns false (out untouched) for a zero or non-finite q. Accuracy: a few ulps.
inline bool rotation_from_quaternion(double w, double x, double y, double z, Matrix3& out) {
  // Scaled by its largest component first, so no length overflows or underflows.
  const double big = std::max(std::max(std::abs(w), std::abs(x)), std::max(std::abs(y), std::abs(z)));
  if (!std::isfinite(big) || !(big > 0)) return false;
  w /= big, x /= big, y /= big, z /= big;
  const double s = 2 / (w * w + x * x + y * y + z * z);
  out = {1 - s * (y * y + z * z), s * (x * y - w * z),     s * (x * z + w * y),
         s * (x * y + w * z),     1 - s * (x * x + z * z), s * (y * z - w * x),
         s * (x * z - w * y),     s * (y * z + w * x),     1 - s * (x * x + y * y)};
  return true;
}

// The unit quaternion (w, x, y, z) of a rotation matrix, w >= 0 (Shepperd's method: the largest
// of the four squared components is computed directly, the others from it). Accuracy: a few ulps.
inline std::array<double, 4> quaternion_from_rotation(const Matrix3& r) {
  const double trace = r[0] + r[4] + r[8];
  std::array<double, 4> q;
  if (trace >= r[0] && trace >= r[4] && trace >= r[8]) {
    const double s = 2 * std::sqrt(1 + trace);
    q = {s / 4, (r[7] - r[5]) / s, (r[2] - r[6]) / s, (r[3] - r[1]) / s};
  } else if (r[0] >= r[4] && r[0] >= r[8]) {
    const double s = 2 * std::sqrt(1 + r[0] - r[4] - r[8]);
    q = {(r[7] - r[5]) / s, s / 4, (r[1] + r[3]) / s, (r[2] + r[6]) / s};
  } else if (r[4] >= r[8]) {
    const double s = 2 * std::sqrt(1 + r[4] - r[0] - r[8]);
    q = {(r[2] - r[6]) / s, (r[1] + r[3]) / s, s / 4, (r[5] + r[7]) / s};
  } else {
    const double s = 2 * std::sqrt(1 + r[8] - r[0] - r[4]);
    q = {(r[3] - r[1]) / s, (r[2] + r[6]) / s, (r[5] + r[7]) / s, s / 4};
  }
  if (q[0] < 0)
    for (double& c : q) c = -c;
  return q;
}

// The Hamilton product a b of quaternions (w, x, y, z): the rotation of b, then of a.
inline std::array<double, 4> quaternion_product(const std::array<double, 4>& a, const std::array<double, 4>& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

// R = Rz(alpha) Ry(beta) Rz(gamma), radians.
inline Matrix3 rotation_from_zyz(double alpha, double beta, double gamma) {
  const double z[3] = {0, 0, 1}, y[3] = {0, 1, 0};
  return multiply(multiply(rotation_about_unit_axis(z, alpha), rotation_about_unit_axis(y, beta)),
                  rotation_about_unit_axis(z, gamma));
}

// Euler angles (radians) about the axes order names: three of 'X', 'Y', 'Z', no axis twice in a
// row ("XYZ", "ZYX", "ZXZ", ...). Intrinsic: each turn is about the axes as already turned,
// R = R1(a) R2(b) R3(c). Extrinsic: each turn is about the fixed axes, R = R3(c) R2(b) R1(a).
// Returns false (out untouched) for another order or a non-finite angle.
inline bool rotation_from_euler(const double angles[3], std::string_view order, bool extrinsic, Matrix3& out) {
  if (order.size() != 3) return false;
  Matrix3 turns[3];
  for (int k = 0; k < 3; ++k) {
    const char c = order[k];
    if ((c != 'X' && c != 'Y' && c != 'Z') || (k > 0 && c == order[k - 1]) || !std::isfinite(angles[k])) return false;
    const double axis[3] = {c == 'X' ? 1.0 : 0.0, c == 'Y' ? 1.0 : 0.0, c == 'Z' ? 1.0 : 0.0};
    turns[k] = rotation_about_unit_axis(axis, angles[k]);
  }
  out = extrinsic ? multiply(multiply(turns[2], turns[1]), turns[0]) : multiply(multiply(turns[0], turns[1]), turns[2]);
  return true;
}

}  // namespace zhf::runtime
