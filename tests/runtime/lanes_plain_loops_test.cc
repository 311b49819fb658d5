// runtime/lanes.h's portable path (compilers without GNU vector types), forced with
// ZHF_LANES_PLAIN_LOOPS for this whole test program (a program must not mix the two paths'
// definitions of the same inline templates): the float and double rotations against the
// independent reference (Ivanic-Ruedenberg, sh/), at the tolerances of the vector-type path.
#define ZHF_LANES_PLAIN_LOOPS
#include <random>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "zhf/runtime/lanes.h"
#include "zhf/runtime/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"
#include "zhf_kernels.h"

namespace zhf {
namespace {

template <class T>
typename runtime::KernelSet<T>::Kernel lanes_kernel(int order) {
  return gen::with_order(order, [](auto n) -> typename runtime::KernelSet<T>::Kernel {
    if constexpr (gen::kHasLanes<decltype(n)::value>) return runtime::lanes_kernels<decltype(n)::value, T>().rotate;
    return nullptr;
  });
}

TEST(LanesPlainLoops, FloatAndDoubleAgainstTheReference) {
  std::mt19937_64 rng(5);
  sh::Normal<> normal;
  for (int order = 3; order <= 8; ++order) {
    const auto in_float = lanes_kernel<float>(order);
    const auto in_double = lanes_kernel<double>(order);
    ASSERT_TRUE(in_float && in_double) << "order " << order;
    const int n = order * order;
    for (int trial = 0; trial < 200; ++trial) {
      // The double kernel and the reference turn by the same rotation; the float kernel by its
      // float rounding, whose error kFloatRotation covers.
      const sh::RotationMatrix m = sh::random_rotation(rng);
      float r[9];
      double r_wide[9];
      for (int i = 0; i < 9; ++i) r[i] = float(r_wide[i] = m(i / 3, i % 3));
      Eigen::VectorXd f(n);
      for (int i = 0; i < n; ++i) f[i] = normal(rng);
      f /= f.norm();
      for (int i = 0; i < n; ++i) f[i] = float(f[i]);  // both kernels get these exact values
      const Eigen::VectorXd reference = sh::apply_band_matrices(sh::ivanic_ruedenberg(m, order), f);
      float in[64], out[64];
      double in_wide[64], out_wide[64];
      for (int i = 0; i < n; ++i) in_wide[i] = in[i] = float(f[i]);
      in_float(r, in, out);
      in_double(r_wide, in_wide, out_wide);
      for (int i = 0; i < n; ++i) {
        ASSERT_NEAR(out[i], reference[i], runtime::tolerance::kFloatRotation) << "float, order " << order << " trial " << trial << " index " << i;
        ASSERT_NEAR(out_wide[i], reference[i], runtime::tolerance::kDouble) << "double, order " << order << " trial " << trial << " index " << i;
      }
    }
  }
}

}  // namespace
}  // namespace zhf
