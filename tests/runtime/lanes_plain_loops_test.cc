// runtime/lanes.h's portable path (compilers without GNU vector types), forced with
// ZHF_LANES_PLAIN_LOOPS for this whole test program (a program must not mix the two paths'
// definitions of the same inline templates): its default float rotation against its double one.
#define ZHF_LANES_PLAIN_LOOPS
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "zhf/runtime/lanes.h"
#include "zhf/runtime/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf_kernels.h"

namespace zhf {
namespace {

constexpr double kFloatTarget = runtime::tolerance::kFloatRotation;  // as for the vector-type path

template <class T>
typename runtime::KernelSet<T>::Kernel lanes_kernel(int order) {
  return gen::with_order(order, [](auto n) -> typename runtime::KernelSet<T>::Kernel {
    if constexpr (gen::kHasLanes<decltype(n)::value>) return runtime::lanes_kernels<decltype(n)::value, T>().rotate;
    return nullptr;
  });
}

TEST(LanesPlainLoops, FloatWithinTheTargetOfDouble) {
  std::mt19937_64 rng(5);
  sh::Normal<> normal;
  for (int order = 3; order <= 8; ++order) {
    const auto plain = lanes_kernel<float>(order);
    const auto wide = lanes_kernel<double>(order);
    for (int trial = 0; trial < 200; ++trial) {
      double q[4], norm = 0;
      for (double& v : q) {
        v = normal(rng);
        norm += v * v;
      }
      norm = std::sqrt(norm);
      const double w = q[0] / norm, x = q[1] / norm, y = q[2] / norm, z = q[3] / norm;
      const float r[9] = {float(1 - 2 * (y * y + z * z)), float(2 * (x * y - w * z)), float(2 * (x * z + w * y)),
                          float(2 * (x * y + w * z)), float(1 - 2 * (x * x + z * z)), float(2 * (y * z - w * x)),
                          float(2 * (x * z - w * y)), float(2 * (y * z + w * x)), float(1 - 2 * (x * x + y * y))};
      float in[64], out[64];
      double r_wide[9], in_wide[64], reference[64];
      for (int i = 0; i < order * order; ++i) in_wide[i] = in[i] = float(normal(rng) / order);
      for (int i = 0; i < 9; ++i) r_wide[i] = r[i];
      plain(r, in, out);
      wide(r_wide, in_wide, reference);
      for (int i = 0; i < order * order; ++i)
        ASSERT_NEAR(out[i], reference[i], kFloatTarget) << "order " << order << " trial " << trial << " index " << i;
    }
  }
}

}  // namespace
}  // namespace zhf
