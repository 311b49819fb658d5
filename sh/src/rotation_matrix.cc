#include "zhf/sh/rotation_matrix.h"

#include <cmath>

#include <Eigen/Geometry>
#include <Eigen/SVD>

namespace zhf::sh {

Matrix3 rotation_about_axis(const Eigen::Vector3d& axis, double angle) {
  return Matrix3(Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix());
}

Matrix3 rotation_from_zyz(double alpha, double beta, double gamma) {
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d y = Eigen::Vector3d::UnitY();
  return rotation_about_axis(z, alpha) * rotation_about_axis(y, beta) * rotation_about_axis(z, gamma);
}

Matrix3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Quaterniond q;
  do {
    q.coeffs() << normal(rng), normal(rng), normal(rng), normal(rng);
  } while (q.norm() < 1e-6);
  q.normalize();
  return Matrix3(q.toRotationMatrix());
}

Eigen::Vector3d random_direction(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Vector3d v;
  do {
    v << normal(rng), normal(rng), normal(rng);
  } while (v.norm() < 1e-6);
  return v.normalized();
}

RotationDefect measure_rotation_defect(const Matrix3& m) {
  RotationDefect defect;
  defect.finite = m.allFinite();
  if (!defect.finite) return defect;
  defect.orthonormality = (m * m.transpose() - Matrix3::Identity()).cwiseAbs().maxCoeff();
  defect.determinant = m.determinant();
  return defect;
}

Matrix3 nearest_rotation(const Matrix3& m) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  const Eigen::Matrix3d v = svd.matrixV();
  // Flip the axis of least stretch if needed so the result is proper (det +1).
  if ((u * v.transpose()).determinant() < 0) u.col(2) = -u.col(2);
  return Matrix3(u * v.transpose());
}

}  // namespace zhf::sh
