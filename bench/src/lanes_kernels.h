// The lobe-parallel kernels (runtime/lanes.h) for zhf bench, in their own translation unit so
// that it alone can be built for the host's SIMD width (cmake -DZHF_BENCH_ARCH=native): it
// shares no inline code with the rest of the binary.
#pragma once

#include <string>

namespace zhf::bench {

using FloatKernel = void (*)(const float*, const float*, float*);

// rotate_lanes of a generated order with lanes tables (nullptr for the others), at the tables'
// lobe stage or, with all_float, all in float.
FloatKernel lanes_kernel(int order, bool all_float);
// The tables' lobe stage (runtime::LobeStage as an int), or -1 when the order has no lanes tables.
int lanes_stage(int order);
// The -march this unit was built with ("" for the toolchain's default).
std::string lanes_arch();

}  // namespace zhf::bench
