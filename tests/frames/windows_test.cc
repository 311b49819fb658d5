// The other needlet windows (frames/windows.h) against independent computations: the spline step
// against a numerical integral of the cubic B-spline, the partition of unity, the Mexican
// window's square sums against a plain sum over levels and its exact period in log_B l, and the
// kernels' energy outside a cap against a fine rule in the angle.
#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "zhf/frames/limits.h"
#include "zhf/frames/windows.h"
#include "zhf/runtime/conventions.h"
#include "zhf/tolerances/tolerances.h"
#include "test_tolerances.h"

namespace zhf::frames {
namespace {

using zhf::tolerance::kNeedletWindow;

// The centred cubic B-spline on [-2, 2].
double cubic_bspline(double s) {
  const double a = std::abs(s);
  if (a >= 2) return 0;
  if (a >= 1) return std::pow(2 - a, 3) / 6;
  return (4 - 6 * a * a + 3 * a * a * a) / 6;
}

TEST(Windows, SplineStepIsTheIntegralOfTheCubicBSpline) {
  for (double u = -1.2; u <= 1.2; u += 0.0137) {
    // Simpson on 2000 panels from -2 to 2u, per piece of the spline (smooth within each).
    const double top = 2 * std::max(-1.0, std::min(1.0, u));
    double integral = 0;
    for (double a = -2; a < top; a += 1) {
      const double b = std::min(top, a + 1), h = (b - a) / 2000;
      double sum = cubic_bspline(a) + cubic_bspline(b);
      for (int i = 1; i < 2000; ++i) sum += cubic_bspline(a + i * h) * (i % 2 ? 4 : 2);
      integral += sum * h / 3;
    }
    EXPECT_NEAR(spline_step(u), integral, zhf::tolerance::kSplineStepAgainstSimpson) << "u " << u;
    EXPECT_NEAR(spline_step(u) + spline_step(-u), 1.0, kNeedletWindow) << "u " << u;
  }
  EXPECT_EQ(spline_step(-1), 0.0);
  EXPECT_EQ(spline_step(1), 1.0);
  EXPECT_EQ(spline_step(0), 0.5);
}

TEST(Windows, SplineWindowsArePartitionOfUnity) {
  constexpr int kLmax = 2000;
  for (double dilation : {1.2, 2.0, 3.0}) {
    const Window w{WindowKind::kSpline, dilation, 1};
    std::vector<double> sum(kLmax + 1, 0.0);
    for (const WindowValue& v : window_values(w, kLmax)) {
      ASSERT_GT(v.l, std::pow(dilation, v.j - 1) - 1e-9) << "B " << dilation << ", level " << v.j << ", band " << v.l;
      ASSERT_LT(v.l, std::pow(dilation, v.j + 1) + 1e-9) << "B " << dilation << ", level " << v.j << ", band " << v.l;
      sum[v.l] += v.value * v.value;
    }
    for (int l = 1; l <= kLmax; ++l) {
      ASSERT_NEAR(sum[l], 1.0, kNeedletWindow) << "B " << dilation << ", band " << l;
      ASSERT_NEAR(window_square_sum(w, l), 1.0, kNeedletWindow) << "B " << dilation << ", band " << l;
    }
  }
}

TEST(Windows, MexicanSquareSumsAreFrameBoundsNotOne) {
  for (int p : {1, 2, 3}) {
    const Window w{WindowKind::kMexican, 2.0, p};
    double least = 1e300, most = 0;
    for (int l = 1; l <= 1000; ++l) {
      double plain = 0;  // every level from far below to far above
      for (int j = -80; j <= 80; ++j) {
        const double x = l / std::pow(2.0, j);
        if (x < 100) plain += std::pow(x, 4 * p) * std::exp(-2 * x * x);  // beyond: below 1e-4000
      }
      const double sum = window_square_sum(w, l);
      ASSERT_NEAR(sum / plain, 1.0, zhf::tolerance::kWindowSquareSum) << "p " << p << ", band " << l;
      // With B = 2 the levels of band 2l are band l's shifted by one: the same sum.
      if (2 * l <= 1000) {
        ASSERT_NEAR(window_square_sum(w, 2 * l) / sum, 1.0, zhf::tolerance::kWindowSquareSum) << "p " << p << ", band " << l;
      }
      least = std::min(least, sum);
      most = std::max(most, sum);
    }
    EXPECT_GT(least, 0.0) << "p " << p;
    EXPECT_GT(most / least, 1.01) << "p " << p;  // a frame, not a tight one
  }
}

TEST(Windows, KernelEnergyOutsideACapMatchesAFineRuleInTheAngle) {
  for (WindowKind kind : {WindowKind::kStandard, WindowKind::kSpline, WindowKind::kMexican}) {
    const Window w{kind, 2.0, 1};
    const int j = 3;
    const BandRange bands = bands_of_level(w, j);
    std::vector<double> b(bands.last + 1, 0.0);
    for (int l = bands.first; l <= bands.last; ++l) b[l] = window_value(w, l / std::pow(2.0, j));
    // K_j(theta) by the Legendre three-term recurrence, its square integrated by the midpoint
    // rule in theta (sin theta d theta) on 200 000 panels.
    auto kernel = [&](double t) {
      double before = 1, legendre = t, k = b[0] / (4 * runtime::kPi) + b[1] * 3 / (4 * runtime::kPi) * t;  // P_0, P_1
      for (int l = 2; l <= bands.last; ++l) {
        const double next = ((2 * l - 1) * t * legendre - (l - 1) * before) / l;
        before = legendre;
        legendre = next;
        k += b[l] * (2 * l + 1) / (4 * runtime::kPi) * legendre;
      }
      return k;
    };
    auto energy_beyond = [&](double radius) {
      constexpr int kPanels = 200000;
      const double h = (runtime::kPi - radius) / kPanels;
      double sum = 0;
      for (int i = 0; i < kPanels; ++i) {
        const double theta = radius + (i + 0.5) * h;
        const double k = kernel(std::cos(theta));
        sum += k * k * std::sin(theta) * h;
      }
      return 2 * runtime::kPi * sum;
    };
    const double total = energy_beyond(0);
    for (double radius : {0.1, 0.3, 1.0}) {
      const double expected = energy_beyond(radius) / total;
      EXPECT_NEAR(kernel_energy_outside(w, j, radius) / expected, 1.0, zhf::tolerance::kCapEnergyAgainstMidpoint) << window_kind_name(kind) << ", radius " << radius;
    }
    EXPECT_EQ(kernel_energy_outside(w, j, runtime::kPi), 0.0) << window_kind_name(kind);
  }
}

TEST(Windows, BadParametersAreRefused) {
  EXPECT_THROW(window_value(Window{WindowKind::kMexican, 2.0, 0}, 1.0), std::invalid_argument);
  EXPECT_THROW(window_value(Window{WindowKind::kMexican, 2.0, frames::kMaxMexicanOrder + 1}, 1.0), std::invalid_argument);
  EXPECT_THROW(window_value(Window{WindowKind::kSpline, 1.0, 1}, 1.0), std::invalid_argument);
  EXPECT_THROW(kernel_energy_outside(Window{WindowKind::kStandard, 2.0, 1}, 2, 0.0), std::invalid_argument);
  EXPECT_THROW(window_values(Window{WindowKind::kSpline, 2.0, 1}, -1), std::invalid_argument);
  WindowKind kind;
  EXPECT_FALSE(parse_window_kind("gaussian", kind));
  ASSERT_TRUE(parse_window_kind("mexican", kind));
  EXPECT_EQ(kind, WindowKind::kMexican);
}

}  // namespace
}  // namespace zhf::frames
