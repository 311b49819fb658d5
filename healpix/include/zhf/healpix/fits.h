// HEALPix maps in FITS files (Gorski et al. 2005; the layout healpy and the HEALPix packages
// write), read and written through cfitsio.
//
// Read: the first extension is a binary table whose header says PIXTYPE = 'HEALPIX', ORDERING =
// 'RING' or 'NESTED' (or 'NEST'), and NSIDE (1..kMaxHealpixNside; a power of two for NESTED);
// INDXSCHM, when present, is 'IMPLICIT' and FIRSTPIX / LASTPIX, when present, 0 and 12 Nside^2 - 1.
// The map is the first column, 12 Nside^2 values in table order (any repeat count, e.g. healpy's
// 1024 values per row), of a float, double or integer type (TSCAL / TZERO applied, as cfitsio
// does). Other columns (Q, U, hit counts) are ignored. Refused: anything else in the file after the
// table, a column whose length is not 12 Nside^2, NaN or infinite pixels, integer null pixels.
// UNSEEN pixels (-1.6375e30, healpy's marker of missing data) are reported, not refused: the caller
// decides (a mask may cover them).
//
// Written: an empty primary HDU and one binary table extension of one double column SIGNAL
// (1024 values a row when 12 Nside^2 is a multiple of 1024, else one), PIXTYPE, ORDERING, NSIDE,
// FIRSTPIX, LASTPIX, INDXSCHM = 'IMPLICIT', OBJECT = 'FULLSKY'. Reading it back gives the same
// doubles bit for bit.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "zhf/healpix/limits.h"

namespace zhf::healpix {

enum class HealpixOrdering { kRing, kNested };

struct HealpixMap {
  std::int64_t nside = 0;
  HealpixOrdering ordering = HealpixOrdering::kRing;
  std::vector<double> pixels;   // 12 nside^2 values in `ordering`
  std::int64_t unseen = 0;      // pixels holding UNSEEN
  std::int64_t first_unseen = -1;
};

// healpy's and HEALPix's marker of a missing pixel, and how near a value counts as it (a float
// file stores it rounded).
inline constexpr double kHealpixUnseen = -1.6375e30;
bool is_unseen(double value);

// 12 nside^2.
std::int64_t healpix_pixels(std::int64_t nside);

// Throws InputError naming the source and what is wrong (keyword, pixel index).
HealpixMap read_healpix_map(const std::string& path);
// The same from the file's bytes (for fuzzing and tests).
HealpixMap parse_healpix_map(const std::string& bytes, const std::string& source);

// The FITS file's bytes. Throws std::invalid_argument for an nside outside 1..kMaxHealpixNside (a
// power of two when nested) or a pixel count that is not 12 nside^2.
std::string encode_healpix_map(const HealpixMap& map);
// encode_healpix_map written by zhf's rules (a temporary beside the target, then renamed).
void write_healpix_map(const std::string& path, const HealpixMap& map);

}  // namespace zhf::healpix
