// The sizes frames/ works to: designs, cubatures, projections, frames, needlets and the transfer
// experiment. Readers and commands check these before any work starts, so a hostile or mistaken
// input is refused at once, never half-done (the runtime's own limits, which every library shares,
// are in runtime/limits.h; scripts/check_one_place.py refuses a limit defined anywhere but a
// library's limits.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "zhf/runtime/limits.h"

namespace zhf::frames {

// Design strengths searched (efficient designs of 1302 points at t = 50); points in a point-set
// file and design starts; Gauss product cubatures (64 Gauss-Legendre nodes, the most sh/'s root
// finder gives); projection orders; frame reports' and the tight-frame rotation's bands.
inline constexpr int kMaxDesignStrength = 100;
inline constexpr int kMaxDesignPoints = 100000;
inline constexpr int kMaxDesignStarts = 100000;
inline constexpr int kMaxCubatureDegree = 126;
inline constexpr int kMaxProjectionOrder = 64;
inline constexpr int kMaxFrameBand = 63;
inline constexpr int kMaxTightFrameOrder = 32;
// Needlets: the dilation B (a B closer to 1 asks for ~log(l) / log(B) levels), window bands, the
// band limit L of a needlet frame (its levels need cubatures of degree 2L), look-up table sizes,
// and the degree of a localisation profile (zhf needlets profile, the windows' localisation).
inline constexpr double kMinDilation = 1.05, kMaxDilation = 64;
inline constexpr int kMaxNeedletBand = 4096;
inline constexpr int kMaxNeedletFrameBand = 63;
// zhf needlets tables: the table sizes one run compares.
inline constexpr std::size_t kMaxNeedletTableSizes = 16;
inline constexpr int kMinNeedletTableSize = 3, kMaxNeedletTableSize = 1 << 20;
inline constexpr int kMaxProfileBand = 1023;
// The levels zhf needlets profile and a window's localisation look at, and the equatorial cut of
// zhf needlets mask: its half-width in degrees, and the margin beyond it in half-wavelengths of
// the top band.
inline constexpr int kMaxProfileLevel = 16;
inline constexpr int kMaxLocalisationLevel = 12;
inline constexpr double kMinMaskCut = 0.1, kMaxMaskCut = 80;
inline constexpr double kMaxMaskMargin = 64;
// Mexican needlets x^(2p) exp(-x^2): orders p.
inline constexpr int kMaxMexicanOrder = 8;
// zhf needlets prt: vertices per side of the ground grid (64^2 = 4096 vertices: about 80 s here).
inline constexpr int kMaxPrtSide = 64;

// zhf needlets prt --kept: coefficient counts per vertex, each at most the frame's size.
inline constexpr int kMaxPrtKeptCounts = 16;

}  // namespace zhf::frames
