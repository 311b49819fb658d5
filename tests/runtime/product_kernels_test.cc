// The checked-in product and shading kernels (generated/cpp) against runtime/product.h and the
// reference rotation, every generated order, float and double.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "zhf/runtime/product.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"
#include "zhf_kernels.h"
#include "test_tolerances.h"

namespace zhf {
namespace {

using zhf::tolerance::kDouble;
using zhf::tolerance::kFloatProduct;

// Unit-norm inputs: random ones, and truncated deltas (f = y(w) / |y(w)|: every coefficient in
// phase at w, the largest values a unit vector reaches, the Gauss-Fourier kernels' worst case).
std::vector<std::vector<double>> unit_inputs(int order, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  sh::Normal<> normal;
  std::vector<std::vector<double>> out;
  const int n = order * order;
  for (int k = 0; k < 200; ++k) {
    std::vector<double> f(n);
    if (k % 2) {
      const Eigen::Vector3d w = sh::random_direction(rng);
      runtime::eval_sh(order, w.data(), f.data());
    } else {
      for (double& x : f) x = normal(rng);
    }
    double norm = 0;
    for (double x : f) norm += x * x;
    for (double& x : f) x /= std::sqrt(norm);
    out.push_back(f);
  }
  return out;
}

template <int N>
void check_products() {
  using K = gen::Kernels<N>;
  constexpr int n = N * N;
  const runtime::ShProduct product(N);
  // Every pair of basis functions: the kernel's outputs are the Gaunt coefficients themselves.
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      double f[n] = {}, g[n] = {}, h[n];
      f[a] = g[b] = 1;
      K::template product<double>(f, g, h);
      for (int c = 0; c < n; ++c)
        ASSERT_NEAR(h[c], runtime::real_gaunt(a, b, c), kDouble)
            << "order " << N << ", band " << runtime::band_of(c) << ", index " << c << ", basis pair " << a << " " << b;
    }
  const auto inputs = unit_inputs(N, 40 + N);
  for (size_t k = 0; k + 1 < inputs.size(); ++k) {
    const double* f = inputs[k].data();
    const double* g = inputs[k + 1].data();
    double expected[n], expected_square[n], h[n], sq[n];
    float ff[n], gf[n], hf[n], sqf[n];
    for (int i = 0; i < n; ++i) ff[i] = float(f[i]), gf[i] = float(g[i]);
    product.product(f, g, expected);
    product.square(f, expected_square);
    K::template product<double>(f, g, h);
    K::template square<double>(f, sq);
    K::template product<float>(ff, gf, hf);
    K::template square<float>(ff, sqf);
    for (int c = 0; c < n; ++c) {
      const std::string where = "order " + std::to_string(N) + ", band " + std::to_string(runtime::band_of(c)) + ", index " +
                                std::to_string(c) + ", input " + std::to_string(k);
      ASSERT_NEAR(h[c], expected[c], kDouble) << where;
      ASSERT_NEAR(sq[c], expected_square[c], kDouble) << where << " (square)";
      ASSERT_NEAR(hf[c], expected[c], kFloatProduct) << where << " (float)";
      ASSERT_NEAR(sqf[c], expected_square[c], kFloatProduct) << where << " (float square)";
    }
  }
}

template <int N>
void check_shading() {
  using K = gen::Kernels<N>;
  constexpr int n = N * N;
  const auto inputs = unit_inputs(N, 80 + N);
  std::mt19937_64 rng(90 + N);
  const double tolerance = N * zhf::tolerance::kFloatLobeStageWorstUnitInput;
  for (size_t k = 0; k + 1 < inputs.size(); ++k) {
    const sh::RotationMatrix r = sh::random_rotation(rng);
    const Eigen::VectorXd light = Eigen::Map<const Eigen::VectorXd>(inputs[k].data(), n);
    const Eigen::VectorXd rotated = sh::apply_band_matrices(sh::ivanic_ruedenberg(r, N), light);
    const double* t = inputs[k + 1].data();
    double expected = 0;
    for (int i = 0; i < n; ++i) expected += rotated[i] * t[i];
    double rd[9], result[1];
    float rf[9], lf[n], tf[n], resultf[1];
    for (int i = 0; i < 9; ++i) rd[i] = r(i / 3, i % 3), rf[i] = float(rd[i]);
    for (int i = 0; i < n; ++i) lf[i] = float(light[i]), tf[i] = float(t[i]);
    K::template shade<double>(rd, light.data(), t, result);
    ASSERT_NEAR(result[0], expected, kDouble) << "order " << N << ", input " << k;
    K::template shade<float>(rf, lf, tf, resultf);
    ASSERT_NEAR(resultf[0], expected, tolerance) << "order " << N << ", input " << k << " (float)";
    if constexpr (N > 2) {
      double z[n];
      K::template lobe_weights<double>(light.data(), z);
      K::template shade_lobes<double>(rd, z, t, result);
      ASSERT_NEAR(result[0], expected, kDouble) << "order " << N << ", input " << k << " (from lobe weights)";
    }
  }
}

template <int N>
void check_all() {
  check_products<N>();
  check_shading<N>();
}

TEST(ProductKernels, Order2) { check_all<2>(); }
TEST(ProductKernels, Order3) { check_all<3>(); }
TEST(ProductKernels, Order4) { check_all<4>(); }
TEST(ProductKernels, Order5) { check_all<5>(); }
TEST(ProductKernels, Order6) { check_all<6>(); }
TEST(ProductKernels, Order7) { check_all<7>(); }
TEST(ProductKernels, Order8) { check_all<8>(); }

}  // namespace
}  // namespace zhf
