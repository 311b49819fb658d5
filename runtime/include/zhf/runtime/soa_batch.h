// rotate_soa<N>: many vectors, each with its own rotation, Pack<T>::kLanes rotations per step (8
// floats on AVX2) through the generated order-N kernel itself: a Pack is a number to it, so the
// rotation is the same expression graph, verified once, run across lanes. Blocks of steps are
// copied plane by plane out of the strided arrays into a local block (about 70 KiB of stack at
// order 8), so the kernel addresses contiguous packs; the generated rotate_batch_orderN reads its
// 3 + 2 N^2 strided streams directly, which the compiler vectorises only when count is a
// compile-time constant (4 to 6 times slower otherwise).
//
// Layout (structure of arrays, as rotate_batch_orderN): R[k count + v] for the row-major entries
// k < 9 of rotation v, coeffs[i count + v] and rotated[i count + v] for i < N^2. Convention as
// Rotator. Orders whose rotate kernel keeps any lobe stage in T (kLobeStage 0: every shipped
// order, 2..8, whose bands rotate by zxzxz); per lane the accuracy of gen::Kernels<N>::rotate<T>.
// Cost: the kernel's operation count (zhf_orderN.h's banner) per kLanes rotations; no allocation.
#pragma once

#include <cstddef>

#include "zhf/runtime/pack.h"
#include "zhf/runtime/parallel.h"
#include "zhf/runtime/rotator.h"  // gen::Kernels

namespace zhf::runtime {

namespace soa_detail {

// Steps per block. Planes a power of two apart (count = 4096) share cache sets: a step reading its
// 9 + N^2 planes directly evicted its own lines (2x to 5x slower); a block reads one plane at a
// time, in runs of kSoaSteps packs. Measured at orders 3..8: 16 steps (block inputs 14 KiB at
// order 3, 37 KiB at 8) up to 1.3x faster than 4, alike 8 and 32 within 10 %.
inline constexpr int kSoaSteps = 16;

// rotate_soa's items [begin, end). Its arguments are values here, not a closure's references:
// the packs' stores (memcpy) could otherwise alias them and force a reload after every store.
template <int N, class T>
void rotate_range(std::size_t count, const T* R, const T* coeffs, T* rotated, std::size_t begin, std::size_t end) {
  using P = Pack<T>;
  constexpr int L = P::kLanes;
  P r[9], f[N * N], g[N * N];
  // kSoaSteps steps at a time: the inputs copied plane by plane into a local block, the kernel
  // run step by step on it, the outputs copied back plane by plane. Then single steps.
  P in[kSoaSteps][9 + N * N], out[kSoaSteps][N * N];
  std::size_t v = begin;
  for (; v + kSoaSteps * L <= end; v += kSoaSteps * L) {
    for (int k = 0; k < 9; ++k)
      for (int s = 0; s < kSoaSteps; ++s) in[s][k] = P::load(R + k * count + v + s * L);
    for (int i = 0; i < N * N; ++i)
      for (int s = 0; s < kSoaSteps; ++s) in[s][9 + i] = P::load(coeffs + i * count + v + s * L);
    for (int s = 0; s < kSoaSteps; ++s) gen::Kernels<N>::template rotate<P>(in[s], in[s] + 9, out[s]);
    for (int i = 0; i < N * N; ++i)
      for (int s = 0; s < kSoaSteps; ++s) out[s][i].store(rotated + i * count + v + s * L);
  }
  for (; v + L <= end; v += L) {
    for (int k = 0; k < 9; ++k) r[k] = P::load(R + k * count + v);
    for (int i = 0; i < N * N; ++i) f[i] = P::load(coeffs + i * count + v);
    gen::Kernels<N>::template rotate<P>(r, f, g);
    for (int i = 0; i < N * N; ++i) g[i].store(rotated + i * count + v);
  }
  if (v == end) return;
  // The last few: lanes past the end hold the identity and zeros.
  const std::size_t left = end - v;
  T lanes[L];
  for (int k = 0; k < 9; ++k) {
    for (int j = 0; j < L; ++j) lanes[j] = std::size_t(j) < left ? R[k * count + v + j] : T(k % 4 == 0);
    r[k] = P::load(lanes);
  }
  for (int i = 0; i < N * N; ++i) {
    for (int j = 0; j < L; ++j) lanes[j] = std::size_t(j) < left ? coeffs[i * count + v + j] : T(0);
    f[i] = P::load(lanes);
  }
  gen::Kernels<N>::template rotate<P>(r, f, g);
  for (int i = 0; i < N * N; ++i) {
    g[i].store(lanes);
    for (std::size_t j = 0; j < left; ++j) rotated[i * count + v + j] = lanes[j];
  }
}

}  // namespace soa_detail

template <int N, class T>
void rotate_soa(std::size_t count, const T* R, const T* coeffs, T* rotated, int threads = 1) {
  static_assert(gen::Kernels<N>::kLobeStage == 0, "rotate_soa: this order's kernel runs its lobe stage in double");
  parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
    soa_detail::rotate_range<N>(count, R, coeffs, rotated, begin, end);
  });
}

}  // namespace zhf::runtime
