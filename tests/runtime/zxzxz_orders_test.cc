// The table-free zxzxz path (Rotator::zxzxz) at orders to kMaxZxzxzOrder, float and double, against
// the recurrence in long double on random and extreme rotations (the recurrence itself is checked
// against the independent quadrature projection to order 16 in every_method_test.cc), and the
// order limit refused. Also, in the build of this test for x86-64-v3, the float kernels written
// in AVX2 intrinsics: the band rows (runtime/band_rows.h, zxzxz with every band in AVX2 lanes),
// which Rotator::zxzxz takes at orders 4..8 in float, and lanes.h's one register of lobes
// (orders 3 and 4).
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "test_tolerances.h"
#include "zhf/runtime/band_recurrence.h"
#include "zhf/runtime/band_rows.h"
#include "zhf/runtime/lanes.h"
#include "zhf/runtime/rotator.h"
#include "zhf/runtime/table_io.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"
#include "zhf_kernels.h"

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
  const std::vector<double> f_values(f.data(), f.data() + n);
  return test::worst_against_recurrence(r.data(), order, f_values, out.data(), at);
}

TEST(ZxzxzOrders, EveryOrderToTheLimitMatchesTheReference) {
  std::mt19937_64 rng(128);
  for (int order : {1, 2, 3, 4, 5, 6, 7, 8, 9, 16, 33, 64, runtime::kMaxZxzxzOrder}) {
    const auto rf = runtime::Rotator<float>::zxzxz(order);
    const auto rd = runtime::Rotator<double>::zxzxz(order);
    std::vector<std::pair<std::string, sh::RotationMatrix>> rotations = sh::extreme_rotations({});
    for (int k = 0; k < 3; ++k) rotations.push_back({"random " + std::to_string(k), sh::random_rotation(rng)});
    for (const auto& [name, r] : rotations) {
      int at = 0;
      const double float_error = worst_error(rf, r, rng, at);
      EXPECT_LE(float_error, zhf::tolerance::kRuntimeOrdersFloat)
          << "float, order " << order << ", rotation '" << name << "', band " << runtime::band_of(at) << ", index " << at;
      const double double_error = worst_error(rd, r, rng, at);
      EXPECT_LE(double_error, order <= runtime::kMaxDoubleAccurateZxzxzOrder ? zhf::tolerance::kDouble
                                                                              : zhf::tolerance::kHighOrderZxzxzDouble)
          << "double, order " << order << ", rotation '" << name << "', band " << runtime::band_of(at) << ", index " << at;
      if (order == runtime::kMaxZxzxzOrder && name == "random 0")
        ::testing::Test::RecordProperty("float_error_order128", std::to_string(float_error));
    }
  }
}

// A float kernel set of order N on the extreme rotations and 200 random ones, its worst unit input
// and its RGB entry point.
void check_float_kernels(const runtime::KernelSet<float>& kernels, const std::string& path) {
  const auto rotator = runtime::Rotator<float>::with(kernels);
  const int N = kernels.order;
  std::mt19937_64 rng(700 + N);
  std::vector<std::pair<std::string, sh::RotationMatrix>> rotations = sh::extreme_rotations({});
  for (int k = 0; k < 200; ++k) rotations.push_back({"random " + std::to_string(k), sh::random_rotation(rng)});
  for (const auto& [name, r] : rotations) {
    int at = 0;
    EXPECT_LE(worst_error(rotator, r, rng, at), zhf::tolerance::kFloatRotation)
        << path << ", order " << N << ", rotation '" << name << "', band " << runtime::band_of(at) << ", index " << at;
  }
  // The worst unit input, at a few rotations of each kind, against the random-input target times
  // the factor a random unit f is spared (the scalar kernels reach 1.3e-6 at order 8 there).
  for (int k : {0, 5, 20, 40}) {
    const sh::RotationMatrix& r = rotations[k].second;
    std::vector<float> rf(9);
    for (int i = 0; i < 9; ++i) rf[i] = float(r(i / 3, i % 3));
    int row = 0;
    const double e = sh::worst_unit_input_error<float>(
        sh::ivanic_ruedenberg(r, N), [&](const float* in, float* out) { rotator.rotate(rf.data(), in, out); }, &row);
    EXPECT_LE(e, zhf::tolerance::kWorstUnitInputFactor * zhf::tolerance::kFloatRotation)
        << path << ", order " << N << ", rotation '" << rotations[k].first << "', band " << runtime::band_of(row) << ", index "
        << row << ": worst unit input";
  }
  // Three channels are three single rotations, to the bit.
  const std::vector<float> r = {0.36f, 0.48f, -0.8f, -0.8f, 0.6f, 0.0f, 0.48f, 0.64f, 0.6f};
  std::vector<float> in(3 * N * N), out(3 * N * N), one(N * N);
  sh::Normal<> normal;
  for (float& x : in) x = float(normal(rng));
  rotator.rotate_rgb(r.data(), in.data(), out.data());
  for (int c = 0; c < 3; ++c) {
    rotator.rotate(r.data(), in.data() + c * N * N, one.data());
    for (int i = 0; i < N * N; ++i)
      EXPECT_EQ(out[c * N * N + i], one[i]) << path << " rgb, order " << N << ", channel " << c << ", index " << i;
  }
}

TEST(ZxzxzOrders, BandRowsMatchTheReferenceAtEveryOrderTheyHold) {
  if constexpr (runtime::kBandRowsBuilt) {
    check_float_kernels(runtime::bands01_kernels(), "bands01");
    check_float_kernels(runtime::band_rows_kernels<4>(), "band rows");
    check_float_kernels(runtime::band_rows_kernels<5>(), "band rows");
    check_float_kernels(runtime::band_rows_kernels<6>(), "band rows");
    check_float_kernels(runtime::band_rows_kernels<7>(), "band rows");
    check_float_kernels(runtime::band_rows_kernels<8>(), "band rows");
  } else {
    GTEST_SKIP() << "built without AVX2 and FMA: no band rows";
  }
}

// Where AVX2 and FMA are built, lanes.h runs float orders 3 and 4 (lobe stage float) in one
// register of lobes: the same checks as the band rows'.
TEST(ZxzxzOrders, LanesInOneRegisterMatchTheReference) {
  constexpr bool kBuilt = ZHF_RUNTIME_AVX2_FMA;
  static_assert(runtime::lanes_detail::kOneRegister<3, float, gen::LanesTables<3>::kLobeStage> == kBuilt);
  static_assert(runtime::lanes_detail::kOneRegister<4, float, gen::LanesTables<4>::kLobeStage> == kBuilt);
  static_assert(!runtime::lanes_detail::kOneRegister<5, float, int(runtime::LobeStage::kFloat)>);
  static_assert(!runtime::lanes_detail::kOneRegister<4, double, int(runtime::LobeStage::kFloat)>);
  if constexpr (kBuilt) {
    check_float_kernels(runtime::lanes_kernels<3, float>(), "lanes, one register");
    check_float_kernels(runtime::lanes_kernels<4, float>(), "lanes, one register");
  } else {
    GTEST_SKIP() << "built without AVX2 and FMA: the portable lanes kernel (generated_kernels_test)";
  }
}

// zhf_kernels.h's fastest paths are the ones its measured table names (never band rows in
// double), and where band rows are built the run-time paths (from_table, zxzxz) take them at every
// order they hold, and bands 0 and 1 in one register at order 2.
TEST(ZxzxzOrders, FloatPathsTakeBandRowsWhereBuilt) {
  for (int order = 2; order <= 9; ++order) {
    const bool held = runtime::kBandRowsBuilt && order >= runtime::kBandRowsMinOrder && order <= runtime::kBandRowsMaxOrder;
    const bool bands01 = runtime::kBandRowsBuilt && order == 2;
    if (order <= 8) {
      EXPECT_EQ(runtime::Rotator<float>::with(gen::fastest_kernels<float>(order)).path(),
                gen::path_name(gen::fastest_path<float>(order)))
          << "fastest float, order " << order << ", table of " << gen::kBuildIsa;
      EXPECT_EQ(runtime::Rotator<double>::with(gen::fastest_kernels<double>(order)).path(),
                gen::path_name(gen::fastest_path<double>(order)))
          << "fastest double, order " << order << ", table of " << gen::kBuildIsa;
      EXPECT_NE(runtime::Rotator<double>::with(gen::fastest_kernels<double>(order)).path(), "band_rows")
          << "fastest double, order " << order;
    }
    if (order >= runtime::kMinTableOrder) {
      const runtime::LobeTable table = runtime::read_lobe_table(test::checked_in_table(order));
      EXPECT_EQ(runtime::Rotator<float>::from_table(table).path() == "band_rows", held) << "from_table, order " << order;
      EXPECT_EQ(runtime::Rotator<float>::from_table(table).path() == "bands01", bands01) << "from_table, order " << order;
      EXPECT_NE(runtime::Rotator<double>::from_table(table).path(), "band_rows") << "from_table double, order " << order;
    }
    EXPECT_EQ(runtime::Rotator<float>::zxzxz(order).path(), held ? "band_rows" : bands01 ? "bands01" : "zxzxz") << "zxzxz, order " << order;
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
