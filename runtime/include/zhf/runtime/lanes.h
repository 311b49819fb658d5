// The signal-tailored rotation arranged lobe-parallel, for SIMD CPUs: loops over the lobes
// (rotate each by R^T; evaluate the SH there and dot each band with f) whose bodies are the
// same straight-line code for every lobe, so the compiler runs them across SIMD lanes; then
// f' = A_l s per band as a dense multiply of SIMD columns. Orders 3..8.
//
// It uses its own lobe tables (generated zhf_lanes_orderN.h): continuous directions chosen for
// the least float error amplification, not the sparse tables' SH zeros, since a dense SIMD A_l s
// costs less here than the sparse scalar one. With them each step runs in float where the
// float error model allows (LanesTables<N>::kLobeStage), which halves the work per lane.
// The fast choice for one vector per rotation where the build targets AVX2 or wider; zhf_kernels.h
// picks it where zhf bench measured it faster (docs/performance.md).
// Accuracy: within 1e-6 of the reference on random unit inputs at the default stage (tested).
#pragma once

#include <cstddef>
#include <cstring>
#include <type_traits>
#include <utility>

#include "zhf/runtime/lobe_stage.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/rotator.h"

namespace zhf::gen {
// The lobe directions and dense inverses of one order, specialised in zhf_lanes_orderN.h:
// kLobeStage (the cheapest LobeStage the float error model allows), kLobes[2N-1][3] and
// kInverse[N-2][2N-1][2N-1].
template <int N>
struct LanesTables;
}  // namespace zhf::gen

namespace zhf::runtime {

namespace lanes_detail {

// Lobes per loop, padded to a multiple of 8 (AVX float lanes) with copies of lobe 0; also the
// rows of the padded columns of A_l.
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
    c.x[d] = W(gen::LanesTables<N>::kLobes[lobe][0]);
    c.y[d] = W(gen::LanesTables<N>::kLobes[lobe][1]);
    c.z[d] = W(gen::LanesTables<N>::kLobes[lobe][2]);
  }
  return c;
}

// sum_m f_{l,m} y_{l,m}: a fixed trip count, so it unrolls into the loop body; two partial sums
// halve the dependency chain.
template <int L, class W>
inline W band_dot(const W* f, const W* y) {
  W even = 0, odd = 0;
  for (int m = 0; m < 2 * L; m += 2) {
    even += f[L * L + m] * y[L * L + m];
    odd += f[L * L + m + 1] * y[L * L + m + 1];
  }
  return (even + f[L * L + 2 * L] * y[L * L + 2 * L]) + odd;
}

// columns[l - 2][d]: column d of A_l, zero beyond its 2l + 1 rows.
template <int N, class T>
struct DenseColumns {
  alignas(64) T columns[N - 2][2 * N - 1][padded_lobes(N)];
};

template <int N, class T>
constexpr DenseColumns<N, T> dense_columns() {
  DenseColumns<N, T> c{};
  for (int b = 0; b < N - 2; ++b)
    for (int d = 0; d < 2 * N - 1; ++d)
      for (int row = 0; row < 2 * N - 1; ++row) c.columns[b][d][row] = T(gen::LanesTables<N>::kInverse[b][row][d]);
  return c;
}

// out[band L] = A_L s: a sum of whole padded columns scaled by the samples.
template <int N, int L, class T, class W>
inline void band_multiply(const T (&columns)[2 * N - 1][padded_lobes(N)], const W* s, T* out) {
  constexpr int kRows = padded_lobes(N);
#if defined(__GNUC__) && !defined(ZHF_LANES_PLAIN_LOOPS)
  // GCC vectorises the plain loops below across d, with transposes; vector types keep the
  // columns whole.
  typedef T Column __attribute__((vector_size(kRows * sizeof(T))));
  Column even = {}, odd = {};
  for (int d = 0; d < 2 * L + 1; ++d) {
    Column column;
    std::memcpy(&column, columns[d], sizeof column);
    (d % 2 == 0 ? even : odd) += column * T(s[d]);
  }
  const Column sum = even + odd;
  T rows[kRows];
  std::memcpy(rows, &sum, sizeof rows);
#else
  T rows[kRows] = {};
  for (int d = 0; d < 2 * L + 1; ++d)
    for (int row = 0; row < kRows; ++row) rows[row] += columns[d][row] * T(s[d]);
#endif
  for (int m = 0; m < 2 * L + 1; ++m) out[L * L + m] = rows[m];
}

template <int N, class T, class W, int... L>
inline void multiply_bands(const DenseColumns<N, T>& a, const W (*s)[padded_lobes(N)], T* out,
                           std::integer_sequence<int, L...>) {
  (band_multiply<N, L + 2>(a.columns[L], s[L], out), ...);
}

template <int N, class W, int... L>
inline void band_samples(const W* f, const W* y, W (*s)[padded_lobes(N)], int d, std::integer_sequence<int, L...>) {
  ((s[L][d] = band_dot<L + 2>(f, y)), ...);
}

}  // namespace lanes_detail

// rotated = coefficients of f(R^T w), R row-major mapping v to R v; orders 3..8 (include
// zhf_orderN.h and zhf_lanes_orderN.h). Flattened so the SH evaluation is inlined into the lobe
// loop at every order (the loop body must be straight-line code to vectorize).
// kStage is a LobeStage; the default is the table's (zhf_lanes_orderN.h, from the error model
// against the 1e-6 target). A s runs in T.
template <int N, class T, int kStage = gen::LanesTables<N>::kLobeStage>
[[gnu::flatten]] inline void rotate_lanes(const T R[9], const T coeffs[N * N], T rotated[N * N]) {
  using namespace lanes_detail;
  constexpr bool kRotationInDouble = kStage >= int(LobeStage::kDoubleRotation);
  constexpr bool kAllInDouble = kStage == int(LobeStage::kDouble);
  using W = std::conditional_t<kAllInDouble, std::common_type_t<T, double>, T>;
  using Rotated = std::conditional_t<kRotationInDouble, std::common_type_t<T, double>, T>;
  constexpr int kLanes = padded_lobes(N);
  static constexpr LobeColumns<N, Rotated> kColumns = lobe_columns<N, Rotated>();
  static constexpr DenseColumns<N, T> kInverse = dense_columns<N, T>();
  Rotated q[9];
  if constexpr (kAllInDouble) {
    polar_step(R, q);
  } else {
    for (int i = 0; i < 9; ++i) q[i] = R[i];
  }
  W f[N * N];
  for (int i = 0; i < N * N; ++i) f[i] = W(coeffs[i]);
  // The lobes rotated in a loop of their own: fused with the evaluation, a double rotation
  // feeding float lanes vectorises worse.
  alignas(64) W rx[kLanes], ry[kLanes], rz[kLanes];
  for (int d = 0; d < kLanes; ++d) {
    rx[d] = W(q[0] * kColumns.x[d] + q[3] * kColumns.y[d] + q[6] * kColumns.z[d]);
    ry[d] = W(q[1] * kColumns.x[d] + q[4] * kColumns.y[d] + q[7] * kColumns.z[d]);
    rz[d] = W(q[2] * kColumns.x[d] + q[5] * kColumns.y[d] + q[8] * kColumns.z[d]);
  }
  alignas(64) W samples[N - 2][kLanes];  // band l + 2's function at R^T w_d
  for (int d = 0; d < kLanes; ++d) {
    const W dir[3] = {rx[d], ry[d], rz[d]};
    W y[N * N];
    gen::Kernels<N>::template sh_eval<W>(dir, y);
    band_samples<N>(f, y, samples, d, std::make_integer_sequence<int, N - 2>());
  }
  multiply_bands<N>(kInverse, samples, rotated, std::make_integer_sequence<int, N - 2>());
  rotated[0] = coeffs[0];
  rotate_band1(R, coeffs + 1, rotated + 1);
}

// The lanes kernel of order N for a Rotator (its RGB entry point is the scalar kernel's, which
// shares the per-rotation work across channels); stage as in rotate_lanes.
template <int N, class T, int kStage = gen::LanesTables<N>::kLobeStage>
KernelSet<T> lanes_kernels() {
  KernelSet<T> k = scalar_kernels<N, T>();
  k.path = "lanes";
  k.rotate = &rotate_lanes<N, T, kStage>;
  return k;
}

}  // namespace zhf::runtime
