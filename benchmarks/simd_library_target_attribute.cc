// simd_library_bench.cc's "target attribute" variant: this unit is compiled without -march (as
// zhf's baseline path is) and the loop below carries __attribute__((target("avx2,fma"))), which is
// how one source reaches AVX2 with per-function attributes. bench/CMakeLists.txt renames the token
// zhf in this unit (-Dzhf=zhf_target_attribute), as dispatch/ renames each path's namespace:
// otherwise the linker would keep one copy of each kernel template for both units.
#include <cstddef>

#include "simd_library_steps.h"

namespace zhf::bench {

template <int N>
__attribute__((target("avx2,fma"))) void rotate_steps_avx2_attribute(std::size_t count, std::size_t stride,
                                                                      const float* R, const float* in, float* out) {
  rotate_steps<N, runtime::Pack<float>>(count, stride, R, in, out);
}

}  // namespace zhf::bench

// Orders 2..8; the caller checks the order.
void rotate_steps_target_attribute(int order, std::size_t count, std::size_t stride, const float* R, const float* in,
                                   float* out) {
  using namespace zhf::bench;
  switch (order) {
    case 2: return rotate_steps_avx2_attribute<2>(count, stride, R, in, out);
    case 3: return rotate_steps_avx2_attribute<3>(count, stride, R, in, out);
    case 4: return rotate_steps_avx2_attribute<4>(count, stride, R, in, out);
    case 5: return rotate_steps_avx2_attribute<5>(count, stride, R, in, out);
    case 6: return rotate_steps_avx2_attribute<6>(count, stride, R, in, out);
    case 7: return rotate_steps_avx2_attribute<7>(count, stride, R, in, out);
    default: return rotate_steps_avx2_attribute<8>(count, stride, R, in, out);
  }
}
