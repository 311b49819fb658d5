// The checked-in C++ kernels against the double reference rotation, and every variant
// against the scalar kernel.
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "test_tolerances.h"
#include "zhf/runtime/lanes.h"
#include "zhf/runtime/rotator.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/runtime/table_io.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"
#include "zhf_kernels.h"

namespace zhf {
namespace {

constexpr int kTrials = 1000;
// Kernels vs the Ivanic-Ruedenberg reference on unit-norm vectors: 1e-12 in double, 1e-6 in float
// at every order (orders whose float model misses it run their lobe stage in double); at the worst
// unit input, kernels whose lobe stage runs (partly) in float get kFloatLobeStageWorstUnitInput.
constexpr double kDoubleTolerance = zhf::tolerance::kDouble;
constexpr double kFloatTolerance = zhf::tolerance::kFloatRotation;
constexpr double kFloatLobeStageWorstUnitVector = zhf::tolerance::kFloatLobeStageWorstUnitInput;
// Variants that do the same arithmetic in another arrangement (RGB, batch) vs the scalar kernel
// agree exactly where there is no FMA; where there is, the compiler contracts the vectorised batch
// loop otherwise than the scalar kernel (aarch64: 1e-16 apart on unit inputs), so a few roundings
// (test::kContractedRelative). Signal-tailored, dense and the table path reorder sums: kDouble.
constexpr double kSameArithmetic = test::kContractedRelative;

struct Case {
  sh::RotationMatrix r;
  Eigen::VectorXd f;
  Eigen::VectorXd reference;
};

std::vector<Case> cases(int order, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  sh::Normal<> normal;
  std::vector<Case> out;
  for (int k = 0; k < count; ++k) {
    Case c;
    c.r = sh::random_rotation(rng);
    c.f.resize(order * order);
    for (int i = 0; i < c.f.size(); ++i) c.f[i] = normal(rng);
    c.f.normalize();
    c.reference = sh::apply_band_matrices(sh::ivanic_ruedenberg(c.r, order), c.f);
    out.push_back(c);
  }
  return out;
}

template <class T>
std::vector<T> to(const Eigen::VectorXd& v) {
  return std::vector<T>(v.data(), v.data() + v.size());
}
template <class T>
std::vector<T> to(const sh::RotationMatrix& r) {
  std::vector<T> out(9);
  for (int i = 0; i < 9; ++i) out[i] = static_cast<T>(r(i / 3, i % 3));
  return out;
}

template <int N>
using Kernels = gen::Kernels<N>;

// Where each scalar kernel runs its lobe stage (order 2 has no lobes).
template <int N>
constexpr bool kLobeStageInDouble = Kernels<N>::kLobeStage == int(runtime::LobeStage::kDouble);

std::string scientific(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3e", v);
  return text;
}

template <class T>
double max_error(const std::vector<T>& out, const Eigen::VectorXd& expected, int& at) {
  double worst = 0;
  for (int i = 0; i < expected.size(); ++i) {
    const double e = std::abs(double(out[i]) - expected[i]);
    if (!(e <= worst)) {
      worst = e;
      at = i;
    }
  }
  return worst;
}

// The scalar generated kernel, or (lanes) the lobe-parallel one of runtime/lanes.h.
template <int N, class T>
void rotate_with(bool lanes, const T* r, const T* in, T* out) {
  if constexpr (N >= 3) {
    if (lanes) return runtime::rotate_lanes<N, T>(r, in, out);
  }
  Kernels<N>::template rotate<T>(r, in, out);
}

template <int N, class T>
void check_against_reference(double tolerance, bool lanes = false) {
  double worst = 0;
  int worst_index = 0, worst_trial = 0;
  const auto all = cases(N, kTrials, 100 + N);
  for (int k = 0; k < kTrials; ++k) {
    const auto r = to<T>(all[k].r);
    const auto in = to<T>(all[k].f);
    std::vector<T> out(N * N);
    rotate_with<N>(lanes, r.data(), in.data(), out.data());
    int at = 0;
    const double e = max_error(out, all[k].reference, at);
    if (e > worst) {
      worst = e;
      worst_index = at;
      worst_trial = k;
    }
  }
  const int band = runtime::band_of(worst_index);
  EXPECT_LE(worst, tolerance) << (lanes ? "lanes, " : "") << "order " << N << ", band " << band << ", index " << worst_index << ", trial "
                              << worst_trial << (sizeof(T) == 4 ? " (float)" : " (double)");
  ::testing::Test::RecordProperty(std::string(lanes ? "lanes_" : "") + "max_error_order" + std::to_string(N) + (sizeof(T) == 4 ? "_float" : "_double"), scientific(worst));
}

template <int N>
void check_variants() {
  using T = double;
  const auto all = cases(N, 50, 200 + N);
  const runtime::Rotator<T> generated = runtime::Rotator<T>::template of<N>();
  for (size_t k = 0; k < all.size(); ++k) {
    const auto r = to<T>(all[k].r);
    const auto in = to<T>(all[k].f);
    std::vector<T> scalar(N * N), other(N * N);
    Kernels<N>::template rotate<T>(r.data(), in.data(), scalar.data());

    Kernels<N>::template rotate_signal_tailored<T>(r.data(), in.data(), other.data());
    for (int i = 0; i < N * N; ++i) EXPECT_NEAR(other[i], scalar[i], kDoubleTolerance) << "signal-tailored order " << N << " index " << i;

    // RGB: three different channels, each equal to its own scalar rotation.
    std::vector<T> rgb_in(3 * N * N), rgb_out(3 * N * N);
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < N * N; ++i) rgb_in[c * N * N + i] = in[(i + c * 7) % (N * N)] * (c + 1);
    generated.rotate_rgb(r.data(), rgb_in.data(), rgb_out.data());
    for (int c = 0; c < 3; ++c) {
      std::vector<T> expected(N * N);
      Kernels<N>::template rotate<T>(r.data(), rgb_in.data() + c * N * N, expected.data());
      for (int i = 0; i < N * N; ++i)
        EXPECT_NEAR(rgb_out[c * N * N + i], expected[i], kSameArithmetic) << "rgb order " << N << " channel " << c << " index " << i;
    }

    const runtime::DenseRotation<T> dense = generated.dense(r.data());
    dense.apply(in.data(), other.data());
    for (int i = 0; i < N * N; ++i) EXPECT_NEAR(other[i], scalar[i], kDoubleTolerance) << "dense order " << N << " index " << i;

    if (N >= 3) {
      const runtime::Rotator<T> from_json =
          runtime::Rotator<T>::from_table(runtime::read_lobe_table(test::checked_in_table(N)));
      from_json.rotate(r.data(), in.data(), other.data());
      for (int i = 0; i < N * N; ++i) EXPECT_NEAR(other[i], scalar[i], kDoubleTolerance) << "runtime JSON order " << N << " index " << i;
    }
  }
  // The batch runs tiles of 16 doubles: counts below a tile (padded), one tile, a last tile that
  // overlaps the one before it, and all the cases.
  for (const size_t count : {size_t(0), size_t(1), size_t(15), size_t(16), size_t(17), size_t(40), all.size()}) {
    std::vector<T> batch_r(9 * count), batch_in(N * N * count), batch_out(N * N * count);
    for (size_t k = 0; k < count; ++k) {
      const auto r = to<T>(all[k].r);
      const auto in = to<T>(all[k].f);
      for (int i = 0; i < 9; ++i) batch_r[i * count + k] = r[i];
      for (int i = 0; i < N * N; ++i) batch_in[i * count + k] = in[i];
    }
    Kernels<N>::template rotate_batch<T>(count, batch_r.data(), batch_in.data(), batch_out.data());
    for (size_t k = 0; k < count; ++k) {
      const auto r = to<T>(all[k].r);
      const auto in = to<T>(all[k].f);
      std::vector<T> scalar(N * N);
      Kernels<N>::template rotate<T>(r.data(), in.data(), scalar.data());
      for (int i = 0; i < N * N; ++i)
        EXPECT_NEAR(batch_out[i * count + k], scalar[i], kSameArithmetic)
            << "batch order " << N << " of " << count << " vector " << k << " index " << i;
    }
  }
}

template <int N>
void check_composition() {
  using T = double;
  std::mt19937_64 rng(300 + N);
  for (int k = 0; k < 100; ++k) {
    const sh::RotationMatrix r1 = sh::random_rotation(rng), r2 = sh::random_rotation(rng);
    const auto f = to<T>(cases(N, 1, 400 + k)[0].f);
    std::vector<T> step(N * N), twice(N * N), once(N * N);
    Kernels<N>::template rotate<T>(to<T>(r2).data(), f.data(), step.data());
    Kernels<N>::template rotate<T>(to<T>(r1).data(), step.data(), twice.data());
    Kernels<N>::template rotate<T>(to<T>(sh::RotationMatrix(r1 * r2)).data(), f.data(), once.data());
    for (int i = 0; i < N * N; ++i) EXPECT_NEAR(twice[i], once[i], kDoubleTolerance) << "order " << N << " index " << i;
  }
}

template <int N>
void check_eval() {
  std::mt19937_64 rng(500 + N);
  for (int k = 0; k < 100; ++k) {
    const Eigen::Vector3d d = sh::random_direction(rng);
    std::vector<double> expected(N * N), got(N * N);
    runtime::eval_sh(N, d.data(), expected.data());
    Kernels<N>::template sh_eval<double>(d.data(), got.data());
    for (int i = 0; i < N * N; ++i) EXPECT_NEAR(got[i], expected[i], zhf::tolerance::kGeneratedVsRecurrence) << "sh_eval order " << N << " index " << i;
  }
}

// The worst unit input (sh::worst_unit_input_error; the kernel's error at the worst row's unit
// f was measured to match the row norm within 5%) over 200 rotations.
template <int N, class Rotate>
void check_worst_unit_vector(Rotate rotate, double tolerance, const char* path, const char* key) {
  constexpr int kRotations = 200;
  std::mt19937_64 rng(300 + N);
  double worst = 0;
  int worst_index = 0, worst_trial = 0;
  for (int k = 0; k < kRotations; ++k) {
    const sh::RotationMatrix r = sh::random_rotation(rng);
    const auto rf = to<float>(r);
    int row = 0;
    const double e = sh::worst_unit_input_error<float>(
        sh::ivanic_ruedenberg(r, N), [&](const float* in, float* out) { rotate(rf.data(), in, out); }, &row);
    if (e > worst) {
      worst = e;
      worst_index = row;
      worst_trial = k;
    }
  }
  const int band = runtime::band_of(worst_index);
  EXPECT_LE(worst, tolerance) << path << ", order " << N << ", band " << band << ", index " << worst_index
                              << ", rotation " << worst_trial << ": worst unit input";
  ::testing::Test::RecordProperty(std::string(key) + "_worst_unit_vector_order" + std::to_string(N), scientific(worst));
}

template <int N>
void check_worst_unit_vectors() {
  check_worst_unit_vector<N>(&Kernels<N>::template rotate<float>,
                             kLobeStageInDouble<N> ? kFloatTolerance : kFloatLobeStageWorstUnitVector,
                             "scalar", "scalar");
  if constexpr (N >= 3) {
    check_worst_unit_vector<N>(runtime::rotate_lanes<N, float>,
                               gen::LanesTables<N>::kLobeStage == int(runtime::LobeStage::kDouble) ? kFloatTolerance
                                                                                                    : kFloatLobeStageWorstUnitVector,
                               "lanes", "lanes");
    // With the whole lobe stage in double the worst case is within the random-input target.
    check_worst_unit_vector<N>(runtime::rotate_lanes<N, float, 2>, kFloatTolerance, "lanes, lobe stage double",
                               "lanes_stage2");
  }
}

// The Rotator on the fastest path zhf_paths.h picks (its measured table for this build's
// instruction set), held to the same targets; fastest_rotator<N, T>() and the run-time
// fastest_rotator<T>(order) of zhf_kernels.h are the same rotator.
template <int N>
void check_fastest_path() {
  const auto rotator = gen::fastest_rotator<N, float>();
  EXPECT_EQ(rotator.path(), gen::path_name(gen::fastest_path<float>(N))) << "order " << N << ", table of " << gen::kBuildIsa;
  EXPECT_EQ(gen::fastest_rotator<float>(N).path(), rotator.path()) << "order " << N;
  double worst = 0;
  for (const Case& c : cases(N, 200, 600 + N)) {
    const auto r = to<float>(c.r);
    const auto in = to<float>(c.f);
    std::vector<float> out(N * N);
    rotator.rotate(r.data(), in.data(), out.data());
    int at = 0;
    worst = std::max(worst, max_error(out, c.reference, at));
  }
  EXPECT_LE(worst, kFloatTolerance) << "fastest path, order " << N;
}

template <int N>
void check_all() {
  check_fastest_path<N>();
  check_against_reference<N, double>(kDoubleTolerance);
  check_against_reference<N, float>(kFloatTolerance);
  if (N >= 3) {
    check_against_reference<N, double>(kDoubleTolerance, /*lanes=*/true);
    check_against_reference<N, float>(kFloatTolerance, /*lanes=*/true);
  }
  check_worst_unit_vectors<N>();
  check_variants<N>();
  check_composition<N>();
  check_eval<N>();
}

TEST(GeneratedKernels, Order2) { check_all<2>(); }
TEST(GeneratedKernels, Order3) { check_all<3>(); }
TEST(GeneratedKernels, Order4) { check_all<4>(); }
TEST(GeneratedKernels, Order5) { check_all<5>(); }
TEST(GeneratedKernels, Order6) { check_all<6>(); }
TEST(GeneratedKernels, Order7) { check_all<7>(); }
TEST(GeneratedKernels, Order8) { check_all<8>(); }

}  // namespace
}  // namespace zhf
