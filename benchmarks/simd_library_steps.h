// The loop that simd_library_bench.cc times for every vector type: count rotations of order N in
// rotate_soa's layout (R[k stride + v], in and out [i stride + v]), one step of V::kLanes
// rotations at a time, the inputs loaded straight from the planes, the generated kernel run with
// V as its number type. The same loop for every V, so the kernels' code is all that differs.
// V: default-constructible, V(double) broadcasts, V::load(const float*), store(float*) const,
// V::kLanes, the arithmetic operators, select_positive and reciprocal_sqrt (found by ADL).
#pragma once

#include <cstddef>

#include "zhf_kernels.h"

namespace zhf::bench {

template <int N, class V>
void rotate_steps(std::size_t count, std::size_t stride, const float* R, const float* in, float* out) {
  for (std::size_t v = 0; v + V::kLanes <= count; v += V::kLanes) {
    V r[9], f[N * N], g[N * N];
    for (int k = 0; k < 9; ++k) r[k] = V::load(R + k * stride + v);
    for (int i = 0; i < N * N; ++i) f[i] = V::load(in + i * stride + v);
    zhf::gen::Kernels<N>::template rotate<V>(r, f, g);
    for (int i = 0; i < N * N; ++i) g[i].store(out + i * stride + v);
  }
}

}  // namespace zhf::bench
