// Every order range and input size zhf accepts, in one place. Readers and commands check these
// before any work starts, so a hostile or mistaken input is refused at once, never half-done.
// Order N = N bands = N^2 coefficients.
#pragma once

#include <cstddef>

namespace zhf::runtime {

// SH evaluation: the normalised recurrences stay finite in float below order 64 (|Q| < 5e12).
// Also the bound for coefficient files and the reference rotations.
inline constexpr int kMaxShOrder = 64;

// Lobe tables: order 2 is the empty table (band 1 rotates as a vector); 32 is the largest the
// search and the run-time path were measured at (condition 205, float error 8e-7).
inline constexpr int kMinTableOrder = 2;
inline constexpr int kMaxTableOrder = 32;
// Candidate directions and the sparsity search need a lobe band: order 3 up. Order 32 has 6.4
// million candidates; above it their tables no longer fit in memory.
inline constexpr int kMinSearchOrder = 3;
inline constexpr int kMaxSearchOrder = kMaxTableOrder;

// Emitted kernels: generated/ holds orders 2..8 (compiled into the runtime); emit, generate,
// scenes and verify go up to 12, where a kernel file reaches megabytes.
inline constexpr int kMinGeneratedOrder = 2;
inline constexpr int kMaxGeneratedOrder = 8;
inline constexpr int kMaxEmitOrder = 12;
// The lobe-parallel kernel (lanes.h) and its tables.
inline constexpr int kMinLanesOrder = 3;
inline constexpr int kMaxLanesOrder = 8;
// Threads a caller may ask for (--threads, threads=): the bound on every thread pool zhf starts.
inline constexpr int kMaxThreads = 256;

// Input files, by kind: checked before they are read (the largest checked-in table, order 32,
// is 0.9 MiB; a coefficient file of this size holds tens of millions of numbers).
inline constexpr std::size_t kMaxTableBytes = std::size_t(16) << 20;
inline constexpr std::size_t kMaxSceneBytes = std::size_t(1) << 20;
inline constexpr std::size_t kMaxManifestBytes = std::size_t(4) << 20;
inline constexpr std::size_t kMaxCoefficientBytes = std::size_t(64) << 20;

}  // namespace zhf::runtime
