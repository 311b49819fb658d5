// Whether this build targets AVX2 and FMA with GCC or Clang (ZHF_RUNTIME_AVX2_FMA, 1 or 0), with
// the intrinsics where it does: the hand-vectorised float kernels (band_rows.h, lanes.h's one
// register of lobes) exist only in such builds; everything else has portable paths.
#pragma once

#if defined(__GNUC__) && defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#define ZHF_RUNTIME_AVX2_FMA 1
#else
#define ZHF_RUNTIME_AVX2_FMA 0
#endif
