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

// Reading a report back (zhf bench --from, the plots): its size, notes, rows and op counts; an
// existing plot is read up to this size to see whether zhf wrote it.
inline constexpr std::size_t kMaxReportBytes = std::size_t(16) << 20;
inline constexpr std::size_t kMaxReportNotes = 1000, kMaxReportRows = std::size_t(1) << 20;
inline constexpr long long kMaxReportOps = 1LL << 40;
inline constexpr std::size_t kMaxPlotBytes = std::size_t(64) << 20;

}  // namespace zhf::bench
