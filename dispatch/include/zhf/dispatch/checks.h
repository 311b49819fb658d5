// Input checks of many numbers on the instruction-set path in use (isa.h), so that checking a batch
// costs what its rotation's path makes it cost: a caller built for baseline x86-64 checking through
// runtime/finite.h directly pays 2-3x more per value than the AVX2 or AVX-512 path (about 8 % of
// an order-6 rotation's time).
#pragma once

#include <cstddef>

namespace zhf::dispatch {

// Whether p[0], ..., p[count - 1] are all finite (runtime::all_finite): one pass over the values.
bool all_finite(const float* p, std::size_t count);
bool all_finite(const double* p, std::size_t count);

}  // namespace zhf::dispatch
