// The HEALPix maps healpix/ reads and analyses. Readers and commands check these before any work
// starts, so a hostile or mistaken input is refused at once, never half-done (the runtime's own
// limits, which every library shares, are in runtime/limits.h; scripts/check_one_place.py refuses a
// limit defined anywhere but a library's limits.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "zhf/runtime/limits.h"

namespace zhf::healpix {

// FITS maps: Nside (12 Nside^2 pixels: 805 million, 6.4 GB as doubles, at the limit) and the bytes
// of the headers before the map's table (a map's are a few kilobytes).
inline constexpr long long kMaxHealpixNside = 8192;
inline constexpr std::size_t kMaxHealpixHeaderBytes = std::size_t(1) << 20;
// Jacobi steps of a map's analysis (healpy's iter; 3 is its default and usually enough).
inline constexpr int kMaxHealpixIterations = 20;

// The FITS standard's ranges: NAXIS and TFIELDS up to 999, BITPIX +-8..64.
inline constexpr long long kMaxFitsAxes = 999, kMaxFitsFields = 999, kMaxFitsBitpix = 64;

}  // namespace zhf::healpix
