// The lobe-parallel kernels (runtime/lanes.h) for zhf bench, in their own translation unit so
// that it alone can be built for the host's SIMD width (cmake -DZHF_BENCH_ARCH=native): it
// shares no inline code with the rest of the binary.
#pragma once

#include <string>

namespace zhf::bench {

using FloatKernel = void (*)(const float*, const float*, float*);

// Orders 3..8; each step where the lanes tables put it or, with all_float, in float.
FloatKernel lanes_kernel(int order, bool all_float);
int lanes_stage(int order);
// The -march this unit was built with ("" for the toolchain's default).
std::string lanes_arch();

}  // namespace zhf::bench
