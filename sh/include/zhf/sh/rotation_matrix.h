// 3x3 rotation helpers. A rotation R is row-major and maps a direction v to R v; rotating
// an SH function f by R gives g(w) = f(R^T w).
#pragma once

#include <cstdint>
#include <random>

#include <Eigen/Core>
#include <Eigen/LU>

namespace zhf::sh {

using Matrix3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

Matrix3 rotation_about_axis(const Eigen::Vector3d& axis, double angle);
// R = Rz(alpha) Ry(beta) Rz(gamma).
Matrix3 rotation_from_zyz(double alpha, double beta, double gamma);
// Uniform (Haar) random rotation from a unit quaternion.
Matrix3 random_rotation(std::mt19937_64& rng);
// Uniform random unit vector.
Eigen::Vector3d random_direction(std::mt19937_64& rng);

// How far M is from a proper rotation.
struct RotationDefect {
  double orthonormality = 0;  // max |M M^T - I|
  double determinant = 0;
  bool finite = true;
};
RotationDefect measure_rotation_defect(const Matrix3& m);

// Nearest proper rotation in the Frobenius norm (polar decomposition via SVD).
Matrix3 nearest_rotation(const Matrix3& m);

}  // namespace zhf::sh
