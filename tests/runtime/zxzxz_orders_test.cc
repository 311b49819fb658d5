// The table-free zxzxz path (Rotator::zxzxz) at orders to kMaxZxzxzOrder, float and double, against
// the recurrence in long double on random and extreme rotations (the recurrence itself is checked
// against the independent quadrature projection to order 16 in every_method_test.cc), and the
// order limit refused.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "zhf/runtime/band_recurrence.h"
#include "zhf/runtime/rotator.h"
#include "zhf/runtime/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/rotation_matrix.h"

namespace zhf {
namespace {

template <class T>
double worst_error(const runtime::Rotator<T>& rotator, const sh::RotationMatrix& r, std::mt19937_64& rng, int& at) {
  const int order = rotator.order(), n = order * order;
  sh::Normal<> normal;
  Eigen::VectorXd f(n);
  for (int i = 0; i < n; ++i) f[i] = normal(rng);
  f.normalize();
  std::vector<T> rt(9), in(n), out(n);
  for (int i = 0; i < 9; ++i) rt[i] = T(r(i / 3, i % 3));
  for (int i = 0; i < n; ++i) in[i] = T(f[i]), f[i] = double(in[i]);
  rotator.rotate(rt.data(), in.data(), out.data());
  // The reference in long double: in double the recurrence's rounding reaches ~5e-7 at l = 127.
  const auto bands = runtime::recurrence_band_matrices<long double>(r.data(), order);
  double worst = 0;
  for (int l = 0; l < order; ++l)
    for (int i = 0; i < 2 * l + 1; ++i) {
      long double expected = 0;
      for (int j = 0; j < 2 * l + 1; ++j) expected += bands[l][i * (2 * l + 1) + j] * f[l * l + j];
      const double error = double(std::abs(out[l * l + i] - expected));
      if (error > worst) worst = error, at = l * l + i;
    }
  return worst;
}

TEST(ZxzxzOrders, EveryOrderToTheLimitMatchesTheReference) {
  std::mt19937_64 rng(128);
  for (int order : {1, 2, 3, 9, 16, 33, 64, runtime::kMaxZxzxzOrder}) {
    const auto rf = runtime::Rotator<float>::zxzxz(order);
    const auto rd = runtime::Rotator<double>::zxzxz(order);
    std::vector<std::pair<std::string, sh::RotationMatrix>> rotations = sh::extreme_rotations({});
    for (int k = 0; k < 3; ++k) rotations.push_back({"random " + std::to_string(k), sh::random_rotation(rng)});
    for (const auto& [name, r] : rotations) {
      int at = 0;
      const double float_error = worst_error(rf, r, rng, at);
      EXPECT_LE(float_error, runtime::tolerance::kRuntimeOrdersFloat)
          << "float, order " << order << ", rotation '" << name << "', band " << runtime::band_of(at) << ", index " << at;
      const double double_error = worst_error(rd, r, rng, at);
      EXPECT_LE(double_error, order <= runtime::kMaxDoubleAccurateZxzxzOrder ? runtime::tolerance::kDouble
                                                                              : runtime::tolerance::kHighOrderZxzxzDouble)
          << "double, order " << order << ", rotation '" << name << "', band " << runtime::band_of(at) << ", index " << at;
      if (order == runtime::kMaxZxzxzOrder && name == "random 0")
        ::testing::Test::RecordProperty("float_error_order128", std::to_string(float_error));
    }
  }
}

TEST(ZxzxzOrders, OrdersAboveTheLimitAreRefusedByName) {
  for (int order : {0, runtime::kMaxZxzxzOrder + 1}) {
    try {
      runtime::Rotator<float>::zxzxz(order);
      ADD_FAILURE() << "order " << order << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("order " + std::to_string(order) + " is outside 1.." +
                                           std::to_string(runtime::kMaxZxzxzOrder)),
                std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace zhf
