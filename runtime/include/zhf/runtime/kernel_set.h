// KernelSet<T>: one implementation of an order's single-rotation entry points, as plain function
// pointers, for a Rotator (rotator.h) to call: the generated kernels (rotator.h), the lanes kernel
// (lanes.h) or the band rows (band_rows.h, with order 2's bands 0 and 1 in one register).
#pragma once

namespace zhf::runtime {

template <class T>
struct KernelSet {
  using Kernel = void (*)(const T*, const T*, T*);
  int order = 0;
  const char* path = "";         // which implementation: "scalar" (generated kernels), "lanes" (lanes.h), "band_rows" or "bands01" (band_rows.h)
  Kernel rotate = nullptr;       // (R, in[N^2], out[N^2])
  Kernel rotate_rgb = nullptr;   // (R, in[3][N^2], out[3][N^2]) as flat planar arrays
};

}  // namespace zhf::runtime
