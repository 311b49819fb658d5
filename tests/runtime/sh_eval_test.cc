#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "test_tolerances.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/slow_reference.h"

// The one SH recurrence (runtime/sh_eval.h) against the slow long-double paths of sh/.
namespace zhf::runtime {
namespace {

using namespace zhf::tolerance;
namespace slow = sh::slow;

struct Angles {
  double theta, phi;
};

std::vector<Angles> test_angles() {
  std::vector<Angles> angles = {{0, 0}, {M_PI, 0}, {M_PI / 2, 0}, {M_PI / 2, M_PI / 2}, {1e-9, 0.3}, {M_PI - 1e-9, -2.0}};
  std::mt19937_64 rng(7);
  auto u = [](std::mt19937_64& g) { return sh::uniform01(g); };
  for (int i = 0; i < 40; ++i) angles.push_back({std::acos(2 * u(rng) - 1), 2 * M_PI * u(rng) - M_PI});
  return angles;
}

TEST(ShEval, BandOneIsScaledYZX) {
  const double c = std::sqrt(3 / (4 * M_PI));
  const double dir[3] = {0.48, 0.6, 0.64};
  double y[4];
  eval_sh(2, dir, y);
  EXPECT_NEAR(y[0], 0.5 / std::sqrt(M_PI), kExactToRounding);
  EXPECT_NEAR(y[1], c * 0.6, kExactToRounding);
  EXPECT_NEAR(y[2], c * 0.64, kExactToRounding);
  EXPECT_NEAR(y[3], c * 0.48, kExactToRounding);
}

TEST(ShEval, MatchesClosedFormForEveryLmUpTo12) {
  constexpr int kOrder = 13;
  for (const Angles& a : test_angles()) {
    double dir[3];
    direction_from_angles(a.theta, a.phi, dir);
    const float dir_f[3] = {float(dir[0]), float(dir[1]), float(dir[2])};
    // The float evaluation is held against the double one at the same float-rounded direction:
    // the rounding of the direction itself moves y_12^0 near a pole by up to l(l+1)/2 eps_f |y|
    // (4e-6), which is the input's error, not the evaluator's.
    const double dir_rounded[3] = {dir_f[0], dir_f[1], dir_f[2]};
    std::vector<double> fast(coefficient_count(kOrder)), at_rounded(coefficient_count(kOrder));
    std::vector<float> fast_f(coefficient_count(kOrder));
    eval_sh(kOrder, dir, fast.data());
    eval_sh(kOrder, dir_rounded, at_rounded.data());
    eval_sh(kOrder, dir_f, fast_f.data());
    for (int l = 0; l < kOrder; ++l) {
      std::vector<double> band(2 * l + 1);
      eval_band(l, dir, band.data());
      for (int m = -l; m <= l; ++m) {
        const double slow = static_cast<double>(slow::real_sh(l, m, a.theta, a.phi));
        EXPECT_NEAR(fast[index(l, m)], slow, kDoubleVsClosedForm)
            << "(l, m) = (" << l << ", " << m << ") at theta " << a.theta << " phi " << a.phi;
        // The same recurrence inlined into two callers: the same bits, except where the target
        // fuses multiply-adds (aarch64's fmadd, x86-64 with FMA), which may fuse the two copies
        // differently, so there up to rounding.
#if defined(__FP_FAST_FMA)
        EXPECT_NEAR(band[m + l], fast[index(l, m)], kExactToRounding) << "eval_band (l, m) = (" << l << ", " << m << ")";
#else
        EXPECT_EQ(band[m + l], fast[index(l, m)]) << "eval_band (l, m) = (" << l << ", " << m << ")";
#endif
        EXPECT_NEAR(fast_f[index(l, m)], at_rounded[index(l, m)], kFloatVsClosedForm)
            << "float (l, m) = (" << l << ", " << m << ") at theta " << a.theta << " phi " << a.phi;
      }
    }
  }
}

TEST(ShEval, SlowPathsAgreeUpTo12) {
  for (int l = 0; l <= 12; ++l)
    for (int m = 0; m <= l; ++m)
      for (double theta : {1e-9, 0.05, 0.7, 1.5707963267948966, 2.2, 3.1}) {
        const long double a = slow::closed_form_legendre(l, m, theta);
        const long double b = slow::recurrence_legendre(l, m, theta);
        EXPECT_NEAR(double(a * slow::normalisation(l, m)), double(b * slow::normalisation(l, m)), kSlowPathsAgreement)
            << "(l, m) = (" << l << ", " << m << ") theta = " << theta;
      }
}

TEST(ShEval, OrthonormalUnderExactQuadratureAtOrder16) {
  constexpr int kOrder = 16;
  constexpr int kCount = kOrder * kOrder;
  std::vector<double> nodes, weights;
  sh::gauss_legendre(kOrder + 1, nodes, weights);  // products have degree 2(N-1) <= 2(N+1)-1
  const int phi_count = 2 * kOrder + 2;
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(kCount, kCount);
  std::vector<double> y(kCount);
  for (size_t k = 0; k < nodes.size(); ++k) {
    for (int j = 0; j < phi_count; ++j) {
      const double s = std::sqrt(1 - nodes[k] * nodes[k]);
      const double phi = 2 * M_PI * j / phi_count;
      const double dir[3] = {s * std::cos(phi), s * std::sin(phi), nodes[k]};
      eval_sh(kOrder, dir, y.data());
      const Eigen::Map<Eigen::VectorXd> v(y.data(), kCount);
      gram.noalias() += (weights[k] * 2 * M_PI / phi_count) * v * v.transpose();
    }
  }
  for (int i = 0; i < kCount; ++i)
    for (int j = 0; j < kCount; ++j)
      ASSERT_NEAR(gram(i, j), i == j ? 1.0 : 0.0, kOrthonormality) << "<y_" << i << ", y_" << j << ">";
}

TEST(ShEval, Order64FiniteAndMatchesLongDoubleRecurrence) {
  constexpr int kOrder = 64;
  std::vector<double> y(coefficient_count(kOrder));
  std::vector<float> yf(coefficient_count(kOrder));
  for (const Angles& a : test_angles()) {
    double dir[3];
    direction_from_angles(a.theta, a.phi, dir);
    const float dir_f[3] = {float(dir[0]), float(dir[1]), float(dir[2])};
    eval_sh(kOrder, dir, y.data());
    eval_sh(kOrder, dir_f, yf.data());
    for (int l = 0; l < kOrder; ++l) {
      double band_max = 0;
      std::vector<double> slow_band(2 * l + 1);
      for (int m = -l; m <= l; ++m) {
        slow_band[m + l] = double(slow::real_sh(l, m, a.theta, a.phi, /*use_closed_form=*/false));
        band_max = std::max(band_max, std::abs(slow_band[m + l]));
      }
      for (int m = -l; m <= l; ++m) {
        ASSERT_TRUE(std::isfinite(y[index(l, m)])) << "(l, m) = (" << l << ", " << m << ")";
        ASSERT_TRUE(std::isfinite(yf[index(l, m)])) << "float (l, m) = (" << l << ", " << m << ")";
        EXPECT_NEAR(y[index(l, m)], slow_band[m + l], kOrder64Relative * std::max(band_max, 1.0))
            << "(l, m) = (" << l << ", " << m << ") at theta " << a.theta << " phi " << a.phi;
      }
    }
  }
}

// The run-time paths evaluate with tabulated coefficients: the same values, every (l, m) (up to
// the compiler's contractions, test::kContractedRelative).
TEST(ShEval, TabulatedCoefficientsGiveTheSameValues) {
  constexpr int kOrder = 33;
  const TabulatedLegendreCoefficients table(kOrder);
  std::vector<double> computed(coefficient_count(kOrder)), tabulated(coefficient_count(kOrder));
  for (const Angles& a : test_angles()) {
    double dir[3];
    direction_from_angles(a.theta, a.phi, dir);
    eval_sh(kOrder, dir, computed.data());
    eval_sh(kOrder, dir, tabulated.data(), table);
    for (int i = 0; i < coefficient_count(kOrder); ++i)
      ASSERT_NEAR(tabulated[i], computed[i], test::kContractedRelative * std::max(1.0, std::abs(computed[i])))
          << "band " << band_of(i) << ", index " << i << " at theta " << a.theta;
  }
}

// Q_l^m alone (the Legendre roots) is the same recurrence as every band at once.
TEST(ShEval, OneLegendreFunctionMatchesTheFullRecurrence) {
  constexpr int kOrder = 20;
  for (double z : {-1.0, -0.3, 0.0, 0.55, 1.0})
    for_each_legendre<double>(kOrder, 0.0, 0.0, z, LegendreCoefficients<>{}, [&](int l, int m, double q, double, double) {
      EXPECT_EQ(legendre_q<double>(l, m, z), q) << "Q_" << l << "^" << m << "(" << z << ")";
    });
}

}  // namespace
}  // namespace zhf::runtime
