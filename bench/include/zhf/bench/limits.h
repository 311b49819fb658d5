// What zhf bench measures. Readers and commands check these before any work starts, so a hostile or
// mistaken input is refused at once, never half-done (the runtime's own limits, which every library
// shares, are in runtime/limits.h; scripts/check_one_place.py refuses a limit defined anywhere but
// a library's limits.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "zhf/runtime/limits.h"

namespace zhf::bench {

// Orders: the lobe-path rows stop at 16, where a run still takes minutes.
inline constexpr int kMaxBenchOrder = 16;

}  // namespace zhf::bench
