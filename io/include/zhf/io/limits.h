// The sizes and counts of the files io/ reads: coefficient files, .ply scenes, Radiance .hdr
// images; and how long an interrupted command may take to stop. Readers and commands check these
// before any work starts, so a hostile or mistaken input is refused at once, never half-done (the
// runtime's own limits, which every library shares, are in runtime/limits.h;
// scripts/check_one_place.py refuses a limit defined anywhere but a library's limits.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "zhf/runtime/limits.h"

namespace zhf::io {

// Coefficient files: N^2 values of an order up to runtime::kMaxShOrder, each up to a magnitude
// whose squares and their sums (band energies) stay finite, in a file of up to 64 MiB (tens of
// millions of numbers); channels per vector (grey, RGB, RGBA) there and in scenes, products and
// emitted kernels.
inline constexpr std::size_t kMaxCoefficientCount = std::size_t(runtime::kMaxShOrder) * runtime::kMaxShOrder;
inline constexpr double kMaxCoefficientMagnitude = 1e150;
inline constexpr std::size_t kMaxCoefficientBytes = std::size_t(64) << 20;
inline constexpr int kMaxChannels = 4;
// .ply scenes: header size, properties (all elements together), elements, rows of an element
// (splats), and an ASCII line (1024 properties of up to 60 characters).
inline constexpr std::size_t kMaxPlyHeaderBytes = std::size_t(64) << 10;
inline constexpr std::size_t kMaxPlyProperties = 1024;
inline constexpr std::size_t kMaxPlyElements = 8;
inline constexpr std::uint64_t kMaxPlyVertices = std::uint64_t(1) << 31;
// An element's count in the header, in digits: read before it is converted, so no count wraps.
inline constexpr std::size_t kMaxPlyCountDigits = 10;
inline constexpr std::size_t kMaxPlyAsciiLine = 64 << 10;
// Radiance .hdr images: file and header size, width and height, pixels.
inline constexpr std::size_t kMaxHdrBytes = std::size_t(256) << 20;
inline constexpr std::size_t kMaxHdrHeader = 64 << 10;
inline constexpr int kMaxHdrSide = 32767;
inline constexpr long long kMaxHdrPixels = 1LL << 25;
// Seconds a command may take to stop after SIGINT or SIGTERM before the watchdog removes its
// temporaries and ends it (work that polls stops well within this).
inline constexpr int kInterruptGraceSeconds = 3;

// An output bound for a FIFO or device, read back from its temporary to be written through.
inline constexpr std::size_t kMaxPassThroughBytes = std::size_t(1) << 40;

}  // namespace zhf::io
