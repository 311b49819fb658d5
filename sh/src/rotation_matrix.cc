#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/rotation_matrix.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace zhf::sh {

RotationMatrix rotation_about_axis(const Eigen::Vector3d& axis, double angle) {
  const Eigen::Vector3d u = axis.normalized();
  return to_eigen(runtime::rotation_about_unit_axis(u.data(), angle));
}

RotationMatrix random_rotation(std::mt19937_64& rng) {
  sh::Normal<> normal(0.0, 1.0);
  Eigen::Quaterniond q;
  do {
    q.coeffs() << normal(rng), normal(rng), normal(rng), normal(rng);
  } while (!(q.norm() > 0));
  q.normalize();
  return RotationMatrix(q.toRotationMatrix());
}

Eigen::Vector3d random_direction(std::mt19937_64& rng) {
  sh::Normal<> normal(0.0, 1.0);
  Eigen::Vector3d v;
  do {
    v << normal(rng), normal(rng), normal(rng);
  } while (!(v.norm() > 0));
  return v.normalized();
}

std::vector<std::pair<std::string, RotationMatrix>> extreme_rotations(const std::vector<Eigen::Vector3d>& lobes) {
  const double pi = runtime::kPi;
  std::vector<std::pair<std::string, RotationMatrix>> out = {
      {"identity", RotationMatrix::Identity()},
      {"180 about x", rotation_about_axis(Eigen::Vector3d::UnitX(), pi)},
      {"180 about y", rotation_about_axis(Eigen::Vector3d::UnitY(), pi)},
      {"180 about z", rotation_about_axis(Eigen::Vector3d::UnitZ(), pi)},
      {"180 about (1,1,0)", rotation_about_axis(Eigen::Vector3d(1, 1, 0), pi)},
      {"180 about (1,1,1)", rotation_about_axis(Eigen::Vector3d(1, 1, 1), pi)},
      {"zyz beta=0", rotation_from_zyz(0.4, 0.0, -1.3)},
      {"zyz beta=pi", rotation_from_zyz(0.4, pi, -1.3)},
      {"zyz beta=1e-9", rotation_from_zyz(2.0, 1e-9, 0.5)},  // an input, not a tolerance
      {"1e-7 rad", rotation_about_axis(Eigen::Vector3d(0.3, -0.2, 0.9), 1e-7)},  // an input, not a tolerance
      {"1e-8 rad about z", rotation_about_axis(Eigen::Vector3d::UnitZ(), 1e-8)},  // an input, not a tolerance
  };
  // The turn carrying unit a onto unit b (none needed when they already agree).
  auto carry = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) -> std::pair<bool, RotationMatrix> {
    const Eigen::Vector3d axis = a.cross(b);
    if (axis.norm() < zhf::tolerance::kParallelAxes) return {false, RotationMatrix::Identity()};
    return {true, rotation_about_axis(axis, std::acos(std::clamp(a.dot(b), -1.0, 1.0)))};
  };
  for (std::size_t d = 0; d < lobes.size() && d < 3; ++d) {
    const auto [needed, r] = carry(lobes[d], Eigen::Vector3d::UnitZ());
    if (needed) out.push_back({"lobe " + std::to_string(d) + " onto the pole", r});
  }
  if (lobes.size() >= 2) {
    const auto [needed, r] = carry(lobes[0], lobes[1]);
    if (needed) out.push_back({"lobe 0 onto lobe 1", r});
  }
  return out;
}

}  // namespace zhf::sh
