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

// Bands 0 and 1 in one register: out[0..3] = in[0] and band 1 of the coefficients of f(R^T w), R
// row-major (convention as rotation.h's rotate_band1). Band 1 is c (y, z, x), so out[1..3] are
// rows y, z, x of R u, u = (in[3], in[1], in[2]) = (x, y, z): three cross-lane permutes take those
// rows of R's columns from one 8-float load (R_22 blended in from a broadcast), then one multiply
// and two fused multiply-adds with u's entries broadcast, in rotate_band1's order of terms. Cost
// about 14 instructions, one 4-float store; each output a sum of three products.
inline void rotate_bands01(const float r[9], const float in[4], float out[4]) {
  const __m256 first8 = _mm256_loadu_ps(r);
  auto column = [&](int j) {  // lanes 1..3: R_1j, R_2j, R_0j
    return _mm256_castps256_ps128(_mm256_permutevar8x32_ps(first8, _mm256_setr_epi32(0, 3 + j, (6 + j) % 8, j, 0, 0, 0, 0)));
  };
  const __m128 column2 = _mm_blend_ps(column(2), _mm_broadcast_ss(r + 8), 0x4);
  __m128 sum = _mm_mul_ps(column(1), _mm_broadcast_ss(in + 1));
  sum = _mm_fmadd_ps(column2, _mm_broadcast_ss(in + 2), sum);
  sum = _mm_fmadd_ps(column(0), _mm_broadcast_ss(in + 3), sum);
  _mm_storeu_ps(out, _mm_blend_ps(sum, _mm_load_ss(in), 0x1));
}

}  // namespace zhf::runtime::avx2
#endif
