// rotate_soa<N>: many vectors, each with its own rotation, Pack<T>::kLanes rotations per step (8
// floats on AVX2) through the generated order-N kernel itself: a Pack is a number to it, so the
// rotation is the same expression graph, verified once, run across lanes. The outputs of a block
// of steps are gathered in a local block and copied plane by plane into the strided arrays; the
// inputs are read straight from the planes up to order 4 when the planes spread over the L1
// cache's sets, and otherwise copied plane by plane into the block too (about 70 KiB of stack at
// order 8). The generated rotate_batch_orderN copies through local blocks too, but runs the kernel
// in T, which the compiler vectorises at order 3 and not from order 4 (the zxzxz bands' square
// root and selections): there it is the scalar kernel's speed, about 2x rotate_soa's.
//
// Layout (structure of arrays, as rotate_batch_orderN): R[k stride + v] for the row-major entries
// k < 9 of rotation v, coeffs[i stride + v] and rotated[i stride + v] for i < N^2, v < count;
// stride is count unless given (planes padded past count, or views into wider arrays: values
// between count and stride are neither read nor written). Convention as Rotator. Orders whose
// rotate kernel keeps any lobe stage in T (kLobeStage 0: every shipped order, 2..8, whose bands
// rotate by zxzxz); per lane the accuracy of gen::Kernels<N>::rotate<T>.
// Cost: the kernel's operation count (zhf_orderN.h's banner) per kLanes rotations; no allocation.
// Planes a multiple of 1024 floats apart share the L1 cache's sets, which costs up to order 4 (1.6x
// at order 3): soa_plane_stride gives a stride that avoids it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

#include "zhf/runtime/pack.h"
#include "zhf/runtime/parallel.h"
#include "zhf/runtime/rotator.h"  // gen::Kernels

namespace zhf::runtime {

namespace soa_detail {

// Steps per block. Planes a power of two apart (count = 4096) share cache sets: a step reading its
// 9 + N^2 planes directly evicted its own lines (2x to 5x slower); a block copy reads one plane at
// a time, in runs of kSoaSteps packs. Measured at orders 3..8: 16 steps (block inputs 14 KiB at
// order 3, 37 KiB at 8) up to 1.3x faster than 4, alike 8 and 32 within 10 %.
inline constexpr int kSoaSteps = 16;

// Reading each step's inputs straight from the planes saves the block copy's stores (the limit at
// order 3, where the kernel is short) where the planes do not crowd into a few cache sets: up to
// order 4, with at most kSoaMaxPlanesPerSet input planes in any line-wide window of a set span
// (measured on AMD Zen 4, counts 3000 to 50000, float: order 2 0.7 to 0.9 ns per rotation against
// the block's 1.0 to 1.2, order 3 1.5 to 1.9 against 2.2 to 2.7, order 4 5.2 to 5.7 against 6.4 to
// 7.1; 9 planes per window still faster at order 3, 13 slower at order 4; all 18, a count that is
// a multiple of 1024 floats, 1.8x to 2.2x slower). Above order 4 the kernel is long enough that
// the block's copies cost little, and reading directly was alike or slower (order 8 up to 1.14x).
inline constexpr int kSoaDirectMaxOrder = 4;
inline constexpr int kSoaMaxPlanesPerSet = 8;

// The most of `planes` planes, stride values of `value_bytes` apart, whose offsets within a cache
// set span fall into one window of window_bytes (a line: the planes that share a set; all of them
// where the distance is a multiple of the span).
inline int planes_per_set(std::size_t stride, int planes, std::size_t value_bytes,
                          std::size_t window_bytes = kCacheLineBytes) {
  const std::size_t span = kCacheSetSpanBytes, distance = stride % span * value_bytes % span;
  int most = 0;
  for (int k = 0; k < planes; ++k) {
    int near = 0;
    for (int j = 0; j < planes; ++j)
      near += (span + j * distance % span - k * distance % span) % span < window_bytes;
    most = std::max(most, near);
  }
  return most;
}

// Whether rotate_soa<N> reads its inputs straight from planes stride values apart.
template <int N, class T>
bool reads_planes_directly(std::size_t stride) {
  return N <= kSoaDirectMaxOrder && planes_per_set(stride, 9 + N * N, sizeof(T)) <= kSoaMaxPlanesPerSet;
}

// rotate_soa's items [begin, end), the inputs read straight from the planes where direct. Its
// arguments are values here, not a closure's references: the packs' stores (memcpy) could
// otherwise alias them and force a reload after every store.
template <int N, class T>
void rotate_range(std::size_t stride, const T* R, const T* coeffs, T* rotated, std::size_t begin, std::size_t end,
                  bool direct) {
  using P = Pack<T>;
  constexpr int L = P::kLanes;
  P r[9], f[N * N], g[N * N];
  // kSoaSteps steps at a time: the inputs read straight from the planes or copied plane by plane
  // into a local block, the kernel run step by step, the outputs copied back plane by plane. Then
  // single steps.
  P out[kSoaSteps][N * N];
  std::size_t v = begin;
  auto copy_out = [&] {
    for (int i = 0; i < N * N; ++i)
      for (int s = 0; s < kSoaSteps; ++s) out[s][i].store(rotated + i * stride + v + s * L);
  };
  if (direct) {
    for (; v + kSoaSteps * L <= end; v += kSoaSteps * L) {
      for (int s = 0; s < kSoaSteps; ++s) {
        P step_r[9], step_f[N * N];  // the step's own: r and f, which the tail shares, ran 6 % slower
        for (int k = 0; k < 9; ++k) step_r[k] = P::load(R + k * stride + v + s * L);
        for (int i = 0; i < N * N; ++i) step_f[i] = P::load(coeffs + i * stride + v + s * L);
        gen::Kernels<N>::template rotate<P>(step_r, step_f, out[s]);
      }
      copy_out();
    }
  } else {
    P in[kSoaSteps][9 + N * N];
    for (; v + kSoaSteps * L <= end; v += kSoaSteps * L) {
      for (int k = 0; k < 9; ++k)
        for (int s = 0; s < kSoaSteps; ++s) in[s][k] = P::load(R + k * stride + v + s * L);
      for (int i = 0; i < N * N; ++i)
        for (int s = 0; s < kSoaSteps; ++s) in[s][9 + i] = P::load(coeffs + i * stride + v + s * L);
      for (int s = 0; s < kSoaSteps; ++s) gen::Kernels<N>::template rotate<P>(in[s], in[s] + 9, out[s]);
      copy_out();
    }
  }
  for (; v + L <= end; v += L) {
    for (int k = 0; k < 9; ++k) r[k] = P::load(R + k * stride + v);
    for (int i = 0; i < N * N; ++i) f[i] = P::load(coeffs + i * stride + v);
    gen::Kernels<N>::template rotate<P>(r, f, g);
    for (int i = 0; i < N * N; ++i) g[i].store(rotated + i * stride + v);
  }
  if (v == end) return;
  // The last few: lanes past the end hold the identity and zeros.
  const std::size_t left = end - v;
  T lanes[L];
  for (int k = 0; k < 9; ++k) {
    for (int j = 0; j < L; ++j) lanes[j] = std::size_t(j) < left ? R[k * stride + v + j] : T(k % 4 == 0);
    r[k] = P::load(lanes);
  }
  for (int i = 0; i < N * N; ++i) {
    for (int j = 0; j < L; ++j) lanes[j] = std::size_t(j) < left ? coeffs[i * stride + v + j] : T(0);
    f[i] = P::load(lanes);
  }
  gen::Kernels<N>::template rotate<P>(r, f, g);
  for (int i = 0; i < N * N; ++i) {
    g[i].store(lanes);
    for (std::size_t j = 0; j < left; ++j) rotated[i * stride + v + j] = lanes[j];
  }
}

}  // namespace soa_detail

// With the planes stride values apart. Throws std::invalid_argument where stride < count or a
// plane's offset would not fit a size_t.
template <int N, class T>
void rotate_soa(std::size_t count, std::size_t stride, const T* R, const T* coeffs, T* rotated, int threads = 1) {
  static_assert(gen::Kernels<N>::kLobeStage == 0, "rotate_soa: this order's kernel runs its lobe stage in double");
  if (stride < count)
    throw std::invalid_argument("rotate_soa: stride " + std::to_string(stride) + " is below count " + std::to_string(count));
  if (stride > std::numeric_limits<std::size_t>::max() / std::size_t(9 + N * N))
    throw std::invalid_argument("rotate_soa: stride " + std::to_string(stride) + " is too large for a plane offset");
  const bool direct = soa_detail::reads_planes_directly<N, T>(stride);
  parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
    soa_detail::rotate_range<N>(stride, R, coeffs, rotated, begin, end, direct);
  });
}

template <int N, class T>
void rotate_soa(std::size_t count, const T* R, const T* coeffs, T* rotated, int threads = 1) {
  rotate_soa<N>(count, count, R, coeffs, rotated, threads);
}

// rotate_items<N>: count vectors in the usual layout (R[9 v + k], coeffs[N^2 v + i], rotated
// likewise), each under its own rotation, on rotate_soa's lanes: kLanes vectors at a time are
// transposed into packs through a local block, rotated by the generated order-N kernel on packs
// and transposed back; the last block's spare lanes hold the identity and zeros. A
// KernelSet::Batch (the per-item batch of zhf::dispatch's generated orders). Convention and
// accuracy per lane as gen::Kernels<N>::rotate<T>; cost: the kernel's operation count per kLanes
// vectors, plus (9 + 2 N^2) scalar moves per vector for the transposes; no allocation.
template <int N, class T>
void rotate_items(std::size_t count, const T* R, const T* coeffs, T* rotated) {
  static_assert(gen::Kernels<N>::kLobeStage == 0, "rotate_items: this order's kernel runs its lobe stage in double");
  using P = Pack<T>;
  constexpr std::size_t L = P::kLanes, n = std::size_t(N) * N;
  T lanes[9 + n][L];
  P r[9], f[n], g[n];
  for (std::size_t v = 0; v < count; v += L) {
    const std::size_t used = std::min(L, count - v);
    if (used == L) {
      for (int k = 0; k < 9; ++k)
        for (std::size_t j = 0; j < L; ++j) lanes[k][j] = R[9 * (v + j) + k];
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < L; ++j) lanes[9 + i][j] = coeffs[n * (v + j) + i];
    } else {
      for (std::size_t j = 0; j < L; ++j) {
        for (int k = 0; k < 9; ++k) lanes[k][j] = j < used ? R[9 * (v + j) + k] : T(k % 4 == 0);
        for (std::size_t i = 0; i < n; ++i) lanes[9 + i][j] = j < used ? coeffs[n * (v + j) + i] : T(0);
      }
    }
    for (int k = 0; k < 9; ++k) r[k] = P::load(lanes[k]);
    for (std::size_t i = 0; i < n; ++i) f[i] = P::load(lanes[9 + i]);
    gen::Kernels<N>::template rotate<P>(r, f, g);
    for (std::size_t i = 0; i < n; ++i) g[i].store(lanes[i]);
    for (std::size_t j = 0; j < used; ++j)
      for (std::size_t i = 0; i < n; ++i) rotated[n * (v + j) + i] = lanes[i][j];
  }
}

// A plane stride for count rotations of order N in T: count itself where rotate_soa<N> reads
// planes that far apart directly already, or never does (above kSoaDirectMaxOrder); otherwise the
// smallest multiple of a cache line's values (16 floats, 8 doubles) from count up at which every
// plane's offset within the set span is two lines or more from every other's, at most one span
// past count (4128 for 4096 floats: the planes 128 bytes apart; one line apart, 4112, ran 1.07x
// slower at order 3 on Zen 4), so planes that start on a line all do. Throws std::invalid_argument where that stride would not fit a size_t.
template <int N, class T>
std::size_t soa_plane_stride(std::size_t count) {
  if (N > soa_detail::kSoaDirectMaxOrder || soa_detail::reads_planes_directly<N, T>(count)) return count;
  constexpr std::size_t line = kCacheLineBytes / sizeof(T), span = kCacheSetSpanBytes / sizeof(T);
  if (count > std::numeric_limits<std::size_t>::max() / std::size_t(9 + N * N) - 2 * span)
    throw std::invalid_argument("soa_plane_stride: count " + std::to_string(count) + " is too large");
  // Two lines apart (a stride two lines past a multiple of the span) fits up to 32 planes in the span.
  std::size_t stride = (count + line - 1) / line * line;
  while (soa_detail::planes_per_set(stride, 9 + N * N, sizeof(T), 2 * kCacheLineBytes) > 1) stride += line;
  return stride;
}

}  // namespace zhf::runtime
