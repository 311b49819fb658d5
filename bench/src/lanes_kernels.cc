#include "lanes_kernels.h"

#include "zhf_kernels.h"

namespace zhf::bench {

// Instantiated here, in the unit ZHF_BENCH_ARCH builds for the host.
FloatKernel lanes_kernel(int order, bool all_float) {
  return gen::with_order(order, [all_float](auto n) -> FloatKernel {
    constexpr int N = decltype(n)::value;
    if constexpr (gen::kHasLanes<N>) {
      if (all_float) return &runtime::rotate_lanes<N, float, int(runtime::LobeStage::kFloat)>;
      return &runtime::rotate_lanes<N, float>;
    }
    return nullptr;
  });
}

int lanes_stage(int order) {
  return gen::with_order(order, [](auto n) {
    constexpr int N = decltype(n)::value;
    if constexpr (gen::kHasLanes<N>) return gen::LanesTables<N>::kLobeStage;
    return -1;
  });
}

std::string lanes_arch() { return ZHF_LANES_ARCH; }

}  // namespace zhf::bench
