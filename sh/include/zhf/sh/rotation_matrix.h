// Rotations as Eigen matrices for the reference math and the tests: adapters over the runtime's
// constructions (runtime/rotation.h), random rotations, and the fixed set of extreme rotations
// every method is checked on. A rotation R is row-major and maps a direction v to R v.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "zhf/runtime/rotation.h"
#include "zhf/runtime/sh_eval.h"

namespace zhf::sh {

using RotationMatrix = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

inline RotationMatrix to_eigen(const runtime::Matrix3& r) { return Eigen::Map<const RotationMatrix>(r.data()); }
inline runtime::Matrix3 to_array(const RotationMatrix& r) {
  runtime::Matrix3 out;
  Eigen::Map<RotationMatrix>(out.data()) = r;
  return out;
}

// A right-handed turn by angle (radians) about axis (any length but zero).
RotationMatrix rotation_about_axis(const Eigen::Vector3d& axis, double angle);
// R = Rz(alpha) Ry(beta) Rz(gamma).
inline RotationMatrix rotation_from_zyz(double alpha, double beta, double gamma) {
  return to_eigen(runtime::rotation_from_zyz(alpha, beta, gamma));
}
// Uniform (Haar) random rotation from a unit quaternion.
RotationMatrix random_rotation(std::mt19937_64& rng);
// Uniform random unit vector.
Eigen::Vector3d random_direction(std::mt19937_64& rng);

// The rotations where methods break if they break: identity, half turns about the axes and
// diagonals, Euler gimbal lock (beta = 0, pi, 1e-9), turns of 1e-7 and 1e-8 rad, and, for the
// lobes given, rotations carrying lobes 0..2 onto the pole and lobe 0 onto lobe 1. Named.
std::vector<std::pair<std::string, RotationMatrix>> extreme_rotations(const std::vector<Eigen::Vector3d>& lobes);

}  // namespace zhf::sh
