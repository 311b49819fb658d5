// Checks on the rotation matrices handed to the rotator, and the explicit repair.
//
// Policy: a rotator rotates by proper rotations only. validate_rotation() reports the measured
// defect; debug builds assert it; nearest_rotation() (polar decomposition) is the explicit
// way to accept a matrix that is off by rounding. Reflections (det -1) are rejected: an SH
// reflection is well defined but it is not what these kernels compute, and passing one is
// almost always a handedness bug in the caller.
#pragma once

#include <cmath>
#include <string>

namespace zhf::runtime {

// Default tolerance on max |R R^T - I| and |det R - 1|: float rotation matrices built from
// quaternions or Euler angles carry a few 1e-7.
inline constexpr double kDefaultRotationTolerance = 1e-5;

struct RotationCheck {
  bool ok = false;
  bool finite = false;
  double orthonormality = 0;  // max |R R^T - I|
  double determinant = 0;
  std::string message;        // empty when ok
};

template <class T>
RotationCheck validate_rotation(const T r[9], double tolerance = kDefaultRotationTolerance) {
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
  check.determinant = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                      m[2] * (m[3] * m[7] - m[4] * m[6]);
  if (check.determinant < 0) {
    check.message = "rotation matrix is a reflection (det " + std::to_string(check.determinant) + ")";
  } else if (check.orthonormality > tolerance || std::abs(check.determinant - 1) > tolerance) {
    check.message = "rotation matrix is not orthonormal: max |R R^T - I| = " + std::to_string(check.orthonormality) +
                    ", det = " + std::to_string(check.determinant) + " (tolerance " + std::to_string(tolerance) + ")";
  } else {
    check.ok = true;
  }
  return check;
}

// Nearest proper rotation to r (Frobenius), by the Newton iteration for the polar factor
// X <- (X + X^-T) / 2, which converges quadratically from any nonsingular start.
// Returns false (and leaves out untouched) for singular, non-finite or reflecting input.
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
    if (!(std::abs(det) > 1e-300) || !std::isfinite(det)) return false;
    // X^-T = cofactor matrix / det.
    double change = 0;
    for (int i = 0; i < 9; ++i) {
      const double next = 0.5 * (x[i] + c[i] / det);
      change = std::max(change, std::abs(next - x[i]));
      x[i] = next;
    }
    if (change < 1e-16) break;
  }
  const double det = x[0] * (x[4] * x[8] - x[5] * x[7]) - x[1] * (x[3] * x[8] - x[5] * x[6]) +
                     x[2] * (x[3] * x[7] - x[4] * x[6]);
  if (det < 0) return false;
  for (int i = 0; i < 9; ++i) out[i] = static_cast<T>(x[i]);
  return true;
}

}  // namespace zhf::runtime
