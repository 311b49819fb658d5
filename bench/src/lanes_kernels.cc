#include "lanes_kernels.h"

#include "zhf/runtime/lanes.h"

namespace zhf::bench {

// Instantiated here, in the unit ZHF_BENCH_ARCH builds for the host.
FloatKernel lanes_kernel(int order, bool all_float) { return runtime::lanes_kernel<float>(order, all_float); }

int lanes_stage(int order) { return runtime::lanes_stage(order); }

std::string lanes_arch() { return ZHF_LANES_ARCH; }

}  // namespace zhf::bench
