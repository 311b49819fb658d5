// rotate_soa<N>: many vectors, each with its own rotation, Pack<T>::kLanes rotations per step (8
// floats on AVX2) through the generated order-N kernel itself: a Pack is a number to it, so the
// rotation is the same expression graph, verified once, run across lanes. Each step first copies
// its lanes' inputs out of the strided arrays, so the kernel addresses a small local block; the
// generated rotate_batch_orderN reads its 3 + 2 N^2 strided streams directly, which the compiler
// vectorises only when count is a compile-time constant (4 to 6 times slower otherwise).
//
// Layout (structure of arrays, as rotate_batch_orderN): R[k count + v] for the row-major entries
// k < 9 of rotation v, coeffs[i count + v] and rotated[i count + v] for i < N^2. Convention as
// Rotator. Orders whose rotate kernel keeps any lobe stage in T (kLobeStage 0: every shipped
// order, 2..8, whose bands rotate by zxzxz); per lane the accuracy of gen::Kernels<N>::rotate<T>. Cost: the kernel's
// operation count (zhf_orderN.h's banner) per kLanes rotations; no allocation.
#pragma once

#include <cstddef>

#include "zhf/runtime/pack.h"
#include "zhf/runtime/parallel.h"
#include "zhf/runtime/rotator.h"  // gen::Kernels

namespace zhf::runtime {

template <int N, class T>
void rotate_soa(std::size_t count, const T* R, const T* coeffs, T* rotated, int threads = 1) {
  static_assert(gen::Kernels<N>::kLobeStage == 0, "rotate_soa: this order's kernel runs its lobe stage in double");
  using P = Pack<T>;
  constexpr int L = P::kLanes;
  parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
    P r[9], f[N * N], g[N * N];
    std::size_t v = begin;
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
  });
}

}  // namespace zhf::runtime
