// The lobe search's orders and sizes (candidates/, optimizer/, pipeline/). Readers and commands
// check these before any work starts, so a hostile or mistaken input is refused at once, never
// half-done (the runtime's own limits, which every library shares, are in runtime/limits.h;
// scripts/check_one_place.py refuses a limit defined anywhere but a library's limits.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "zhf/runtime/limits.h"

namespace zhf::candidates {

// Candidate directions and the sparsity search need a lobe band: order 3 up. Order 32 has 6.4
// million candidates; above it their tables no longer fit in memory.
inline constexpr int kMinSearchOrder = 3;
inline constexpr int kMaxSearchOrder = runtime::kMaxTableOrder;
// candidates --json up to this order: its 174242 directions take about 400 MiB to write (order 20
// has 584162 and 1.4 GiB, order 32 6.4 million and 15 GiB).
inline constexpr int kMaxCandidatesJsonOrder = 16;
// The search tabulates candidates' SH values up front when they fit in this many doubles (1 GiB),
// else evaluates them on demand (same results, slower).
inline constexpr std::size_t kMaxTabulatedValues = std::size_t(1) << 27;
// A search's local phase gets at least this much of a time limit (seconds).
inline constexpr double kMinSearchSeconds = 1e-3;

// zhf optimize's search: GA population, generations, stalls (GA and local search), continuous
// starts and the time limit in seconds (generous; the bounds keep counts in an int).
inline constexpr int kMinPopulation = 4, kMaxPopulation = 1000000;
inline constexpr int kMaxGenerations = 100000000;
inline constexpr int kMaxStall = 1000000;
inline constexpr int kMaxSearchStarts = 1000000;
inline constexpr double kMaxSearchTimeLimit = 1e7;

}  // namespace zhf::candidates
