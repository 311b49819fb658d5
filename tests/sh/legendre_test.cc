#include <cmath>

#include <gtest/gtest.h>

#include "zhf/runtime/limits.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/legendre.h"
#include "zhf/sh/slow_reference.h"
#include "test_tolerances.h"

namespace zhf::sh {
namespace {

constexpr double kRootResidualSlow = zhf::tolerance::kRootResidual;
using runtime::kMaxShOrder;

TEST(LegendreRoots, CountIsLMinusMForAllUpTo64) {
  for (int l = 0; l <= kMaxShOrder; ++l) {
    for (int m = 0; m <= l; ++m) {
      const std::vector<double> roots = legendre_roots_theta(l, m);
      ASSERT_EQ(static_cast<int>(roots.size()), l - m) << "P_" << l << "^" << m;
      for (size_t k = 0; k < roots.size(); ++k) {
        ASSERT_GT(roots[k], 0.0) << "P_" << l << "^" << m << " root " << k;
        ASSERT_LT(roots[k], M_PI) << "P_" << l << "^" << m << " root " << k;
        if (k > 0) {
          ASSERT_GT(roots[k], roots[k - 1]) << "P_" << l << "^" << m << " root " << k;
        }
      }
    }
  }
}

TEST(LegendreRoots, VanishInLongDoubleUpTo12) {
  for (int l = 1; l <= 12; ++l)
    for (int m = 0; m <= l; ++m)
      for (double theta : legendre_roots_theta(l, m)) {
        const long double value = slow::normalisation(l, m) * slow::closed_form_legendre(l, m, theta);
        EXPECT_LT(std::abs(double(value)), kRootResidualSlow) << "P_" << l << "^" << m << " at " << theta;
      }
}

// Full double precision: the true root lies within a few ulps, i.e. the function changes
// sign across [theta - 4 ulp, theta + 4 ulp] (checked in long double) at every order.
TEST(LegendreRoots, FullDoublePrecisionUpTo64) {
  for (int l = 1; l <= kMaxShOrder; l += 3)
    for (int m = 0; m <= l; m += 2)
      for (double theta : legendre_roots_theta(l, m)) {
        double lo = theta, hi = theta;
        for (int k = 0; k < 4; ++k) {
          lo = std::nextafter(lo, 0.0);
          hi = std::nextafter(hi, 4.0);
        }
        const long double f_lo = slow::recurrence_legendre(l, m, lo);
        const long double f_hi = slow::recurrence_legendre(l, m, hi);
        EXPECT_TRUE((f_lo <= 0 && f_hi >= 0) || (f_lo >= 0 && f_hi <= 0))
            << "P_" << l << "^" << m << " root " << theta << " not bracketed within 4 ulps";
      }
}

TEST(LegendreRoots, EquatorIsExactAndRootsMirror) {
  const std::vector<double> roots = legendre_roots_theta(7, 2);
  ASSERT_EQ(roots.size(), 5u);
  EXPECT_EQ(roots[2], M_PI / 2);
  EXPECT_EQ(roots[4], M_PI - roots[0]);
}

TEST(LegendreRoots, RejectsBadDegree) {
  EXPECT_THROW(legendre_roots_theta(3, 4), std::invalid_argument);
  EXPECT_THROW(legendre_roots_theta(65, 0), std::invalid_argument);
}

}  // namespace
}  // namespace zhf::sh
