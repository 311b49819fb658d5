// KernelSet<T>: one implementation of an order's single-rotation entry points, as plain function
// pointers, for a Rotator (rotator.h) to call: the generated kernels (rotator.h), the lanes kernel
// (lanes.h) or the band rows (band_rows.h, with order 2's bands 0 and 1 in one register).
#pragma once

#include <cstddef>

namespace zhf::runtime {

template <class T>
struct KernelSet {
  using Kernel = void (*)(const T*, const T*, T*);
  using Batch = void (*)(std::size_t, const T*, const T*, T*);
  int order = 0;
  const char* path = "";         // which implementation: "scalar" (generated kernels), "lanes" (lanes.h), "band_rows" or "bands01" (band_rows.h)
  Kernel rotate = nullptr;       // (R, in[N^2], out[N^2])
  Kernel rotate_rgb = nullptr;   // (R, in[3][N^2], out[3][N^2]) as flat planar arrays
  Batch rotate_batch = nullptr;  // (count, R[9 count], in[N^2 count], out[N^2 count]): rotate on each vector
};

// A Batch for a kernel known when compiled: the loop calls it directly, so each call can inline
// (through KernelSet::rotate every vector is an indirect call, which weighs at small orders).
template <class T, int Order, void (*Rotate)(const T*, const T*, T*)>
void rotate_each(std::size_t count, const T* r, const T* in, T* out) {
  constexpr std::size_t n = std::size_t(Order) * Order;
  for (std::size_t v = 0; v < count; ++v) Rotate(r + 9 * v, in + n * v, out + n * v);
}

}  // namespace zhf::runtime
