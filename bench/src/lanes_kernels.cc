#include "lanes_kernels.h"

#include "zhf/runtime/lanes.h"

namespace zhf::bench {
namespace {

template <int N>
FloatKernel lanes_of(bool float_lobes) {
  return float_lobes ? &runtime::rotate_lanes<N, float, false> : &runtime::rotate_lanes<N, float>;
}

}  // namespace

FloatKernel lanes_kernel(int order, bool float_lobes) {
  switch (order) {
    case 3: return lanes_of<3>(float_lobes);
    case 4: return lanes_of<4>(float_lobes);
    case 5: return lanes_of<5>(float_lobes);
    case 6: return lanes_of<6>(float_lobes);
    case 7: return lanes_of<7>(float_lobes);
    default: return lanes_of<8>(float_lobes);
  }
}

bool lobe_stage_in_double(int order) {
  switch (order) {
    case 3: return runtime::GeneratedOrder<3>::kLobeStageInDouble;
    case 4: return runtime::GeneratedOrder<4>::kLobeStageInDouble;
    case 5: return runtime::GeneratedOrder<5>::kLobeStageInDouble;
    case 6: return runtime::GeneratedOrder<6>::kLobeStageInDouble;
    case 7: return runtime::GeneratedOrder<7>::kLobeStageInDouble;
    default: return runtime::GeneratedOrder<8>::kLobeStageInDouble;
  }
}

std::string lanes_arch() { return ZHF_LANES_ARCH; }

}  // namespace zhf::bench
