#include "lanes_kernels.h"

#include "zhf/runtime/lanes.h"

namespace zhf::bench {

// Instantiated here, in the unit ZHF_BENCH_ARCH builds for the host.
FloatKernel lanes_kernel(int order, bool float_lobes) { return runtime::lanes_kernel<float>(order, float_lobes); }

bool lobe_stage_in_double(int order) { return runtime::lobe_stage_in_double(order); }

std::string lanes_arch() { return ZHF_LANES_ARCH; }

}  // namespace zhf::bench
