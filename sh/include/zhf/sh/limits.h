// The analysis sh/ does for zhf analyze and the Python module. Readers and commands check these
// before any work starts, so a hostile or mistaken input is refused at once, never half-done (the
// runtime's own limits, which every library shares, are in runtime/limits.h;
// scripts/check_one_place.py refuses a limit defined anywhere but a library's limits.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "zhf/runtime/limits.h"

namespace zhf::sh {

// The relative tolerance of analyze (and zhf analyze) goes down to this: double rounding.
inline constexpr double kMinZonalTolerance = 1e-15;

}  // namespace zhf::sh
