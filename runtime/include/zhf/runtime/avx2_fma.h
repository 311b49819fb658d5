// Whether this build targets AVX2 and FMA with GCC or Clang (ZHF_RUNTIME_AVX2_FMA, 1 or 0), with
// the intrinsics and the helpers the hand-vectorised float kernels share where it does: those
// kernels (band_rows.h, lanes.h's one register of lobes) exist only in such builds; everything
// else has portable paths.
#pragma once

#if defined(__GNUC__) && defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#define ZHF_RUNTIME_AVX2_FMA 1
#else
#define ZHF_RUNTIME_AVX2_FMA 0
#endif

#if ZHF_RUNTIME_AVX2_FMA
namespace zhf::runtime::avx2 {

// The first Count lanes of v to p (whole halves, then pairs, then one), nothing past them.
template <int Count>
inline void store_first(float* p, __m256 v) {
  static_assert(Count >= 1 && Count <= 8);
  if constexpr (Count == 8) {
    _mm256_storeu_ps(p, v);
  } else {
    __m128 x = _mm256_castps256_ps128(v);
    int left = Count;
    if (left >= 4) {
      _mm_storeu_ps(p, x);
      p += 4, left -= 4;
      x = _mm256_extractf128_ps(v, 1);
    }
    if (left >= 2) {
      _mm_storel_pi(reinterpret_cast<__m64*>(p), x);
      p += 2, left -= 2;
      x = _mm_movehl_ps(x, x);
    }
    if (left == 1) _mm_store_ss(p, x);
  }
}

}  // namespace zhf::runtime::avx2
#endif
