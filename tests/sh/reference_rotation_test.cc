#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"
#include "test_tolerances.h"

namespace zhf::sh {
namespace {

using runtime::coefficient_count;
using runtime::eval_sh;
using zhf::tolerance::kExactToRounding;
using zhf::tolerance::kPointwise;
using zhf::tolerance::kReferenceAgreement;

Eigen::VectorXd random_coefficients(int order, std::mt19937_64& rng) {
  sh::Normal<> normal(0, 1);
  Eigen::VectorXd f(coefficient_count(order));
  for (int i = 0; i < f.size(); ++i) f[i] = normal(rng);
  return f.normalized();
}

double evaluate(const Eigen::VectorXd& f, int order, const Eigen::Vector3d& w) {
  std::vector<double> y(coefficient_count(order));
  eval_sh(order, w.data(), y.data());
  return Eigen::Map<const Eigen::VectorXd>(y.data(), y.size()).dot(f);
}

// The shared extreme set, and axes next to the poles, where Euler-angle methods break.
std::vector<std::pair<std::string, RotationMatrix>> special_rotations() {
  auto out = extreme_rotations({});
  out.push_back({"axis near north pole", rotation_about_axis(Eigen::Vector3d(1e-9, 0, 1), 0.7)});
  out.push_back({"axis near south pole", rotation_about_axis(Eigen::Vector3d(0, -1e-9, -1), 2.1)});
  return out;
}

void expect_bands_near(const BandMatrices& a, const BandMatrices& b, double tolerance, const std::string& what) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t l = 0; l < a.size(); ++l)
    for (int i = 0; i < a[l].rows(); ++i)
      for (int j = 0; j < a[l].cols(); ++j)
        ASSERT_NEAR(a[l](i, j), b[l](i, j), tolerance)
            << what << ": band " << l << " row m'=" << i - int(l) << " col m=" << j - int(l);
}

TEST(ReferenceRotation, MethodsAgreeAtOrder8) {
  std::mt19937_64 rng(1);
  for (const auto& [name, r] : special_rotations())
    expect_bands_near(ivanic_ruedenberg(r, 8), quadrature_rotation(r, 8), kReferenceAgreement, name);
  for (int i = 0; i < 20; ++i) {
    const RotationMatrix r = random_rotation(rng);
    expect_bands_near(ivanic_ruedenberg(r, 8), quadrature_rotation(r, 8), kReferenceAgreement,
                      "random " + std::to_string(i));
  }
}

TEST(ReferenceRotation, MethodsAgreeAtOrder32) {
  std::mt19937_64 rng(2);
  for (int i = 0; i < 3; ++i) {
    const RotationMatrix r = random_rotation(rng);
    expect_bands_near(ivanic_ruedenberg(r, 32), quadrature_rotation(r, 32), kReferenceAgreement,
                      "random " + std::to_string(i));
  }
}

TEST(ReferenceRotation, ReproducesRotatedFunctionPointwise) {
  constexpr int kOrder = 8;
  std::mt19937_64 rng(3);
  auto rotations = special_rotations();
  for (int i = 0; i < 10; ++i) rotations.push_back({"random " + std::to_string(i), random_rotation(rng)});
  for (const auto& [name, r] : rotations) {
    const Eigen::VectorXd f = random_coefficients(kOrder, rng);
    const Eigen::VectorXd g = apply_band_matrices(ivanic_ruedenberg(r, kOrder), f);
    EXPECT_NEAR(g.norm(), f.norm(), kReferenceAgreement) << name;
    for (int k = 0; k < 20; ++k) {
      const Eigen::Vector3d w = random_direction(rng);
      EXPECT_NEAR(evaluate(g, kOrder, w), evaluate(f, kOrder, r.transpose() * w), kPointwise) << name;
    }
  }
}

TEST(ReferenceRotation, ComposesAsAGroupAction) {
  constexpr int kOrder = 10;
  std::mt19937_64 rng(4);
  for (int i = 0; i < 10; ++i) {
    const RotationMatrix r1 = random_rotation(rng), r2 = random_rotation(rng);
    const Eigen::VectorXd f = random_coefficients(kOrder, rng);
    const Eigen::VectorXd step = apply_band_matrices(ivanic_ruedenberg(r1, kOrder),
                                                     apply_band_matrices(ivanic_ruedenberg(r2, kOrder), f));
    const Eigen::VectorXd once = apply_band_matrices(ivanic_ruedenberg(r1 * r2, kOrder), f);
    for (int c = 0; c < f.size(); ++c) EXPECT_NEAR(step[c], once[c], kReferenceAgreement) << "coefficient " << c;
  }
}

TEST(ReferenceRotation, IdentityIsExact) {
  const BandMatrices bands = ivanic_ruedenberg(RotationMatrix::Identity(), 12);
  for (size_t l = 0; l < bands.size(); ++l)
    EXPECT_LT((bands[l] - Eigen::MatrixXd::Identity(2 * l + 1, 2 * l + 1)).cwiseAbs().maxCoeff(), kExactToRounding)
        << "band " << l;
}

}  // namespace
}  // namespace zhf::sh
