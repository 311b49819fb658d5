// The draws every output depends on are pinned: these numbers come from the generator's raw bits
// alone, so libstdc++, libc++ and MSVC's library give the same designs, verify inputs and pools.
#include <gtest/gtest.h>

#include <cmath>

#include "zhf/sh/random.h"

namespace zhf::sh {
namespace {

TEST(PortableDraws, UniformsComeFromTheTop53Bits) {
  Rng rng(42);
  Rng raw(42);
  for (int i = 0; i < 100; ++i) {
    const double u = uniform01(rng);
    EXPECT_EQ(u, static_cast<double>(raw() >> 11) / 9007199254740992.0) << "draw " << i;
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
  }
}

TEST(PortableDraws, IndicesAreUnbiasedAndPinned) {
  Rng rng(7);
  const int expected[8] = {15, 250, 878, 46, 421, 428, 609, 918};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(uniform_index(rng, 1000), expected[i]) << "draw " << i;
}

TEST(PortableDraws, NormalsArePinned) {
  Rng rng(1);
  Normal<> normal;
  const double expected[6] = {-0.039399956754155314, -0.38683176162103955, -0.24894784633514516,
                               0.68682363917932521,  -0.05464685232137162, -0.79514624370949194};
  for (int i = 0; i < 6; ++i) EXPECT_EQ(normal(rng), expected[i]) << "draw " << i;
}

TEST(PortableDraws, NormalsHaveUnitVariance) {
  Rng rng(3);
  Normal<> normal(2.0, 0.5);
  double sum = 0, squares = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double x = normal(rng);
    sum += x;
    squares += x * x;
  }
  const double mean = sum / n, variance = squares / n - mean * mean;
  // Five standard errors: 0.5 / sqrt(n) for the mean, 0.25 sqrt(2 / n) for the variance.
  EXPECT_NEAR(mean, 2.0, 5 * 0.5 / std::sqrt(double(n)));
  EXPECT_NEAR(variance, 0.25, 5 * 0.25 * std::sqrt(2.0 / n));
}

}  // namespace
}  // namespace zhf::sh
