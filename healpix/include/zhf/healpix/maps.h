// HEALPix maps and zhf's SH coefficients: analysis (map to coefficients), synthesis (coefficients
// to map), pixel orderings and centres. HEALPix's theta (from +z) and phi (from +x towards +y) are
// zhf's; coefficients are zhf's real orthonormal SH without Condon-Shortley phase, index
// l (l + 1) + m (healpy's complex a_lm carry the phase: docs/frames.md gives the conversion).
//
// The pixel geometry (rings, centres, NESTED <-> RING) and the transforms are the HEALPix C++
// library's; tests/healpix checks them against pixel-by-pixel sums of runtime::eval_sh.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "zhf/healpix/fits.h"
#include "zhf/healpix/limits.h"

namespace zhf::healpix {

using Point = std::array<double, 3>;

// The map's pixels in RING order (a copy; NESTED reordered).
std::vector<double> ring_pixels(const HealpixMap& map);
// A map in `ordering` from RING-ordered pixels.
HealpixMap map_from_ring(std::int64_t nside, std::vector<double> ring, HealpixOrdering ordering);

// The signal to analyse: the map's RING pixels times a mask's (same Nside, any ordering, values
// in [0, 1]: 0 drops a pixel, fractions apodise), or the map alone. An UNSEEN pixel must have mask
// 0. Throws runtime::InputError naming the file and pixel (map_name, mask_name) otherwise.
struct MaskedSignal {
  std::int64_t nside = 0;
  std::vector<double> ring;
  std::vector<double> weights;  // the mask's, RING (empty: no mask)
  double sky_fraction = 1;      // mean of the mask
};
MaskedSignal masked_signal(const HealpixMap& map, const std::string& map_name, const HealpixMap* mask, const std::string& mask_name);
// The same from files (mask_path empty: no mask).
MaskedSignal read_masked_signal(const std::string& map_path, const std::string& mask_path);

// The unit vector at a pixel's centre, and the pixel (RING) holding a unit direction.
Point pixel_centre(std::int64_t nside, std::int64_t ring_pixel);
std::int64_t pixel_at(std::int64_t nside, const Point& direction);

// Called between the transforms' passes (to poll an interrupt: it may throw).
using Checkpoint = std::function<void()>;

// The highest band an analysis of a map of this Nside may ask for, 4 Nside (the HEALPix library's
// bound: beyond it the rings cannot tell the bands apart; healpy's default is 3 Nside - 1).
inline int max_analysis_band(std::int64_t nside) { return static_cast<int>(std::min<std::int64_t>(4 * nside, 1 << 30)); }

// The SH coefficients of order N (bands 0..N-1) of a RING map by the pixel quadrature
//   f_lm = (4 pi / N_pix) sum_p f(p) y_l^m(p)
// (healpy's map2alm without ring weights), then `iterations` Jacobi steps f_lm += analysis of
// (map - synthesis of f_lm) (healpy's iter). A map of bands < N comes back to the quadrature's
// accuracy, better with each step while the bands stay well below 2 Nside (docs/frames.md).
// The transforms are the HEALPix library's (libsharp: FFTs along rings, Legendre recurrences;
// OpenMP threads, results independent of their count); the coefficients converted to zhf's
// convention. Cost per pass ~ N_pix log(Nside) + rings N^2; 1 + 2 iterations passes.
// Throws std::invalid_argument for an order outside 1..runtime::kMaxShOrder or above
// max_analysis_band(nside) + 1, iterations
// outside 0..healpix::kMaxHealpixIterations or a pixel count that is not 12 nside^2.
std::vector<double> analyze_map(std::int64_t nside, const std::vector<double>& ring, int order, int iterations,
                                const Checkpoint& checkpoint = {});

// The RING map of coefficients of order N: f(p) = sum f_lm y_l^m(p) at every pixel centre. One pass.
std::vector<double> synthesize_map(std::int64_t nside, const std::vector<double>& sh, const Checkpoint& checkpoint = {});

}  // namespace zhf::healpix
