// The signal-tailored rotation arranged lobe-parallel, for SIMD CPUs: one loop over the lobes
// whose body (rotate the lobe by R^T, evaluate the SH there, dot each band with f) is the same
// straight-line code for every lobe, so the compiler runs it across SIMD lanes; then the sparse
// f' = A s per band. Orders 3..8, from the generated headers' lobe tables, SH evaluation and
// AhatMultiply.
//
// It computes what rotate_signal_tailored_orderN does, with the lobe stage in double exactly
// where the generated kernels have it (kLobeStageInDoubleOrderN), so the accuracy is the same.
// It gives up the generated kernels' per-lobe constant folding (components +-1 or 0) to get
// the lanes: the fast choice for one vector per rotation where the build targets AVX2 or
// wider (-O3 -mavx2 -mfma, or -march=native); with SSE2 only, compare with zhf bench.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "zhf/runtime/polar_step.h"
#include "zhf_order3.h"
#include "zhf_order4.h"
#include "zhf_order5.h"
#include "zhf_order6.h"
#include "zhf_order7.h"
#include "zhf_order8.h"

namespace zhf::runtime {

template <int N>
struct GeneratedOrder;
#define ZHF_GENERATED_ORDER(N)                                                                  \
  template <>                                                                                   \
  struct GeneratedOrder<N> {                                                                    \
    static constexpr bool kLobeStageInDouble = gen::kLobeStageInDoubleOrder##N;                 \
    static constexpr const double (&kLobes)[2 * N - 1][3] = gen::kLobesOrder##N;                \
    template <class T>                                                                          \
    static void sh_eval(const T dir[3], T y[N * N]) { gen::sh_eval_order##N<T>(dir, y); }       \
    template <class T>                                                                          \
    static void lobe_multiply(const T s[N * N], T f[N * N]) { gen::AhatMultiply_order##N<T>(s, f); } \
  };
ZHF_GENERATED_ORDER(3)
ZHF_GENERATED_ORDER(4)
ZHF_GENERATED_ORDER(5)
ZHF_GENERATED_ORDER(6)
ZHF_GENERATED_ORDER(7)
ZHF_GENERATED_ORDER(8)
#undef ZHF_GENERATED_ORDER

namespace lanes_detail {

// Lobes per loop, padded to a multiple of 8 (AVX float lanes) with copies of lobe 0.
constexpr int padded_lobes(int order) { return (2 * order - 1 + 7) / 8 * 8; }

template <int N, class W>
struct LobeColumns {
  alignas(64) W x[padded_lobes(N)];
  alignas(64) W y[padded_lobes(N)];
  alignas(64) W z[padded_lobes(N)];
};

template <int N, class W>
constexpr LobeColumns<N, W> lobe_columns() {
  LobeColumns<N, W> c{};
  for (int d = 0; d < padded_lobes(N); ++d) {
    const int lobe = d < 2 * N - 1 ? d : 0;
    c.x[d] = W(GeneratedOrder<N>::kLobes[lobe][0]);
    c.y[d] = W(GeneratedOrder<N>::kLobes[lobe][1]);
    c.z[d] = W(GeneratedOrder<N>::kLobes[lobe][2]);
  }
  return c;
}

// sum_m f_{l,m} y_{l,m}: a fixed trip count, so it unrolls into the loop body.
template <int L, class W>
inline W band_dot(const W* f, const W* y) {
  W sum = 0;
  for (int m = 0; m < 2 * L + 1; ++m) sum += f[L * L + m] * y[L * L + m];
  return sum;
}

template <int N, class W, int... L>
inline void band_samples(const W* f, const W* y, W (*s)[padded_lobes(N)], int d, std::integer_sequence<int, L...>) {
  ((s[L][d] = band_dot<L + 2>(f, y)), ...);
}

}  // namespace lanes_detail

// rotated = coefficients of f(R^T w), R row-major mapping v to R v; orders 3..8. Flattened so
// the SH evaluation is inlined into the lobe loop at every order (the loop body must be
// straight-line code to vectorize).
// kDoubleLobes overrides where the lobe stage runs (false: float throughout, faster, error up to
// the float model of verify.h).
template <int N, class T, bool kDoubleLobes = GeneratedOrder<N>::kLobeStageInDouble>
[[gnu::flatten]] inline void rotate_lanes(const T R[9], const T coeffs[N * N], T rotated[N * N]) {
  using namespace lanes_detail;
  using W = std::conditional_t<kDoubleLobes, std::common_type_t<T, double>, T>;
  constexpr int kLanes = padded_lobes(N);
  static constexpr LobeColumns<N, W> kColumns = lobe_columns<N, W>();
  W q[9];
  if constexpr (kDoubleLobes) {
    polar_step(R, q);
  } else {
    for (int i = 0; i < 9; ++i) q[i] = R[i];
  }
  W f[N * N];
  for (int i = 0; i < N * N; ++i) f[i] = W(coeffs[i]);
  alignas(64) W samples[N - 2][kLanes];  // band l + 2's function at R^T w_d
  for (int d = 0; d < kLanes; ++d) {
    const W dir[3] = {q[0] * kColumns.x[d] + q[3] * kColumns.y[d] + q[6] * kColumns.z[d],
                      q[1] * kColumns.x[d] + q[4] * kColumns.y[d] + q[7] * kColumns.z[d],
                      q[2] * kColumns.x[d] + q[5] * kColumns.y[d] + q[8] * kColumns.z[d]};
    W y[N * N];
    GeneratedOrder<N>::sh_eval(dir, y);
    band_samples<N>(f, y, samples, d, std::make_integer_sequence<int, N - 2>());
  }
  T s[N * N] = {};
  for (int l = 2; l < N; ++l)
    for (int d = 0; d < 2 * l + 1; ++d) s[l * l + d] = T(samples[l - 2][d]);
  GeneratedOrder<N>::lobe_multiply(s, rotated);
  // Band 0 is invariant; band 1 is c (y, z, x), so its matrix is R on those axes.
  constexpr int kAxisOfM[3] = {1, 2, 0};
  rotated[0] = coeffs[0];
  for (int m = 0; m < 3; ++m) {
    T sum = 0;
    for (int n = 0; n < 3; ++n) sum += R[3 * kAxisOfM[m] + kAxisOfM[n]] * coeffs[1 + n];
    rotated[1 + m] = sum;
  }
}

template <class T>
using LanesKernel = void (*)(const T*, const T*, T*);

namespace lanes_detail {
template <int N, class T>
LanesKernel<T> kernel_of(bool float_lobes) {
  return float_lobes ? &rotate_lanes<N, T, false> : &rotate_lanes<N, T>;
}
}  // namespace lanes_detail

// rotate_lanes for an order known at run time (3..8); float_lobes: the lobe stage in float.
template <class T>
LanesKernel<T> lanes_kernel(int order, bool float_lobes = false) {
  switch (order) {
    case 3: return lanes_detail::kernel_of<3, T>(float_lobes);
    case 4: return lanes_detail::kernel_of<4, T>(float_lobes);
    case 5: return lanes_detail::kernel_of<5, T>(float_lobes);
    case 6: return lanes_detail::kernel_of<6, T>(float_lobes);
    case 7: return lanes_detail::kernel_of<7, T>(float_lobes);
    case 8: return lanes_detail::kernel_of<8, T>(float_lobes);
    default: throw std::invalid_argument("lanes_kernel: order " + std::to_string(order) + " is not in [3, 8]");
  }
}

// Whether the generated kernels (and so rotate_lanes by default) of an order 3..8 run their
// lobe stage in double.
inline bool lobe_stage_in_double(int order) {
  switch (order) {
    case 3: return GeneratedOrder<3>::kLobeStageInDouble;
    case 4: return GeneratedOrder<4>::kLobeStageInDouble;
    case 5: return GeneratedOrder<5>::kLobeStageInDouble;
    case 6: return GeneratedOrder<6>::kLobeStageInDouble;
    case 7: return GeneratedOrder<7>::kLobeStageInDouble;
    case 8: return GeneratedOrder<8>::kLobeStageInDouble;
    default: throw std::invalid_argument("lobe_stage_in_double: order " + std::to_string(order) + " is not in [3, 8]");
  }
}

}  // namespace zhf::runtime
