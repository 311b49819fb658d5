// Numerical extremes through the runtime and the generated kernels (issue: nothing silent).
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "zhf/runtime/rotator.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"
#include "zhf_kernels.h"
#include "test_tolerances.h"

namespace zhf {
namespace {

std::vector<float> to_float(const sh::RotationMatrix& m) {
  std::vector<float> r(9);
  for (int i = 0; i < 9; ++i) r[i] = static_cast<float>(m(i / 3, i % 3));
  return r;
}

// 10^4 successive 0.01 rad rotations about random axes of one order-4 vector through the scalar
// float kernel, against one rotation by the composed matrix in double (runtime/tolerances.h,
// kFloatChain, has what the drift is and is not).
constexpr double kChainTolerance = zhf::tolerance::kFloatChain;

TEST(Extremes, LongChainOfSmallRotationsInFloat) {
  constexpr int kOrder = 4, kSteps = 10000;
  const auto rotator = runtime::Rotator<float>::with(gen::scalar_kernels<float>(kOrder));
  std::mt19937_64 rng(11);
  sh::Normal<> normal;
  Eigen::VectorXd f(kOrder * kOrder);
  for (int i = 0; i < f.size(); ++i) f[i] = normal(rng);
  f.normalize();
  std::vector<float> v(f.data(), f.data() + f.size()), next(v.size());
  sh::RotationMatrix total = sh::RotationMatrix::Identity();
  for (int k = 0; k < kSteps; ++k) {
    const sh::RotationMatrix step = sh::rotation_about_axis(sh::random_direction(rng), 0.01);
    total = step * total;
    rotator.rotate(to_float(step).data(), v.data(), next.data());
    v.swap(next);
  }
  const Eigen::VectorXd expected = sh::apply_band_matrices(sh::ivanic_ruedenberg(total, kOrder), f);
  double error = 0, norm = 0;
  for (int i = 0; i < f.size(); ++i) {
    error = std::max(error, std::abs(v[i] - expected[i]));
    norm += double(v[i]) * v[i];
  }
  EXPECT_LT(error, kChainTolerance) << "after " << kSteps << " steps";
  EXPECT_NEAR(std::sqrt(norm), 1.0, kChainTolerance);
}

TEST(Extremes, NonFiniteCoefficientsPropagateAndNeverCrash) {
  for (int order = 2; order <= 8; ++order) {
    const auto rotator = runtime::Rotator<float>::with(gen::fastest_kernels<float>(order));
    std::vector<float> in(order * order, 0.1f), out(order * order);
    const std::vector<float> r = to_float(sh::rotation_about_axis(Eigen::Vector3d(1, 2, 3), 0.7));
    in.back() = std::numeric_limits<float>::quiet_NaN();
    rotator.rotate(r.data(), in.data(), out.data());
    // The NaN's band is poisoned; the bands below it are untouched.
    const int last = order - 1;
    for (int i = last * last; i < order * order; ++i) EXPECT_TRUE(std::isnan(out[i])) << "order " << order << " index " << i;
    for (int i = 0; i < last * last; ++i) EXPECT_TRUE(std::isfinite(out[i])) << "order " << order << " index " << i;
    in.back() = std::numeric_limits<float>::infinity();
    rotator.rotate(r.data(), in.data(), out.data());
    for (int i = last * last; i < order * order; ++i) EXPECT_FALSE(std::isfinite(out[i])) << "order " << order;
  }
}

TEST(Extremes, HugeTinyAndZeroMagnitudesInFloat) {
  for (int order = 2; order <= 8; ++order) {
    const auto rotator = runtime::Rotator<float>::with(gen::fastest_kernels<float>(order));
    const sh::RotationMatrix m = sh::rotation_about_axis(Eigen::Vector3d(-1, 0.5, 2), 2.2);
    const std::vector<float> r = to_float(m);
    std::mt19937_64 rng(order);
    sh::Normal<> normal;
    Eigen::VectorXd f(order * order);
    for (int i = 0; i < f.size(); ++i) f[i] = normal(rng);
    f.normalize();
    const Eigen::VectorXd g = sh::apply_band_matrices(sh::ivanic_ruedenberg(m, order), f);
    // Scaling commutes with rotation; 1e30 (products stay below FLT_MAX ~3.4e38 since no
    // intermediate exceeds |A| |Y| |f| ~ 1e33) and 1e-30 (normal: FLT_MIN is 1.2e-38).
    for (double scale : {1e30, 1e-30}) {
      std::vector<float> in(f.size()), out(f.size());
      for (int i = 0; i < f.size(); ++i) in[i] = static_cast<float>(f[i] * scale);
      rotator.rotate(r.data(), in.data(), out.data());
      for (int i = 0; i < f.size(); ++i)
        EXPECT_NEAR(out[i] / scale, g[i], zhf::tolerance::kFloatExtremeScale) << "order " << order << " scale " << scale << " index " << i;
    }
    std::vector<float> zero(f.size(), 0.0f), out(f.size(), 1.0f);
    rotator.rotate(r.data(), zero.data(), out.data());
    for (int i = 0; i < f.size(); ++i) EXPECT_EQ(out[i], 0.0f) << "order " << order << " index " << i;
  }
}

// rotation_accepted, the check of many matrices, accepts what validate_rotation accepts: rotations,
// reflections, defects either side of the tolerance, scaled and non-finite matrices.
TEST(Extremes, RotationAcceptedAgreesWithValidate) {
  std::mt19937_64 rng(31);
  std::vector<std::array<double, 9>> matrices;
  for (int k = 0; k < 200; ++k) {
    const sh::RotationMatrix m = sh::random_rotation(rng);
    std::array<double, 9> r;
    for (int i = 0; i < 9; ++i) r[i] = m(i / 3, i % 3);
    matrices.push_back(r);
    std::array<double, 9> changed = r;
    for (int i = 0; i < 3; ++i) changed[i] = -changed[i];  // a reflection
    matrices.push_back(changed);
    changed = r;
    const double defect = zhf::tolerance::kRotationDefect * std::ldexp(1.0, k % 5 - 2);  // 1/4 to 4 times the tolerance
    changed[k % 9] += defect;
    matrices.push_back(changed);
    changed = r;
    for (double& x : changed) x *= 1 + defect;
    matrices.push_back(changed);
  }
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 1e200}) {
    std::array<double, 9> r = matrices[0];
    r[4] = bad;
    matrices.push_back(r);
  }
  for (std::size_t k = 0; k < matrices.size(); ++k)
    for (const runtime::Handedness h : {runtime::Handedness::kProper, runtime::Handedness::kEither}) {
      const bool validated = runtime::validate_rotation(matrices[k].data(), zhf::tolerance::kRotationDefect, h).ok;
      ASSERT_EQ(runtime::rotation_accepted(matrices[k].data(), zhf::tolerance::kRotationDefect, h), validated)
          << "matrix " << k << (h == runtime::Handedness::kEither ? ", either handedness" : ", proper only");
    }
}

TEST(Extremes, ValidateMeasuresTheDefectAndNearestRotationRepairs) {
  const sh::RotationMatrix good = sh::rotation_about_axis(Eigen::Vector3d(0.3, -1, 0.2), 1.1);
  double r[9];
  for (int i = 0; i < 9; ++i) r[i] = good(i / 3, i % 3);
  EXPECT_TRUE(runtime::validate_rotation(r).ok);
  for (double defect : {1e-6, 1e-3, 1e-1}) {
    double bent[9];
    std::copy(r, r + 9, bent);
    bent[1] += defect;
    const runtime::RotationCheck check = runtime::validate_rotation(bent);
    EXPECT_EQ(check.ok, defect < zhf::tolerance::kRotationDefect) << defect;
    EXPECT_GT(check.orthonormality, 0.5 * defect) << defect;
    if (!check.ok) {
      EXPECT_NE(check.message.find("not orthonormal"), std::string::npos) << check.message;
    }
    double fixed[9];
    ASSERT_TRUE(runtime::nearest_rotation(bent, fixed));
    const runtime::RotationCheck repaired = runtime::validate_rotation(fixed, zhf::tolerance::kDouble);
    EXPECT_TRUE(repaired.ok) << repaired.message;
  }
  double reflection[9];
  std::copy(r, r + 9, reflection);
  for (int j = 0; j < 3; ++j) reflection[j] = -reflection[j];
  const runtime::RotationCheck check = runtime::validate_rotation(reflection);
  EXPECT_FALSE(check.ok);
  EXPECT_NEAR(check.determinant, -1.0, zhf::tolerance::kDouble);
  EXPECT_NE(check.message.find("reflection"), std::string::npos);
  double nan_matrix[9];
  std::copy(r, r + 9, nan_matrix);
  nan_matrix[4] = std::nan("");
  EXPECT_FALSE(runtime::validate_rotation(nan_matrix).finite);
  double out[9];
  EXPECT_FALSE(runtime::nearest_rotation(nan_matrix, out));
}

TEST(Extremes, OrdersOneAndTwoNeedNoLobes) {
  const auto rotator = runtime::Rotator<double>::of<2>();
  const sh::RotationMatrix m = sh::rotation_about_axis(Eigen::Vector3d(1, 1, 0), 3.14159265358979323846);
  double r[9], in[4] = {0.5, 0.1, -0.7, 0.3}, out[4];
  for (int i = 0; i < 9; ++i) r[i] = m(i / 3, i % 3);
  rotator.rotate(r, in, out);
  const Eigen::VectorXd g = sh::apply_band_matrices(sh::ivanic_ruedenberg(m, 2), Eigen::Map<Eigen::VectorXd>(in, 4));
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(out[i], g[i], zhf::tolerance::kExactToRounding) << "index " << i;
  const sh::BandMatrices one = sh::ivanic_ruedenberg(m, 1);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0](0, 0), 1.0);
}

}  // namespace
}  // namespace zhf
