// HEALPix maps and zhf's SH coefficients: analysis (map to coefficients), synthesis (coefficients
// to map), pixel orderings and centres. HEALPix's theta (from +z) and phi (from +x towards +y) are
// zhf's; coefficients are zhf's real orthonormal SH without Condon-Shortley phase, index
// l (l + 1) + m (healpy's complex a_lm carry the phase: docs/frames.md gives the conversion).
//
// The pixel geometry (rings, centres, NESTED <-> RING) is the HEALPix C++ library's. Sums run
// ring by ring: a ring's pixels are equally spaced in phi, so a ring costs one Legendre column
// per m (runtime::eval_sh at the ring's theta) and a direct sum over its pixels per m.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "zhf/healpix/fits.h"

namespace zhf::healpix {

using Point = std::array<double, 3>;

// The map's pixels in RING order (a copy; NESTED reordered).
std::vector<double> ring_pixels(const HealpixMap& map);
// A map in `ordering` from RING-ordered pixels.
HealpixMap map_from_ring(std::int64_t nside, std::vector<double> ring, HealpixOrdering ordering);

// The unit vector at a pixel's centre, and the pixel (RING) holding a unit direction.
Point pixel_centre(std::int64_t nside, std::int64_t ring_pixel);
std::int64_t pixel_at(std::int64_t nside, const Point& direction);

// Called between batches of rings (to poll an interrupt: it may throw).
using Checkpoint = std::function<void()>;

// The SH coefficients of order N (bands 0..N-1) of a RING map by the pixel quadrature
//   f_lm = (4 pi / N_pix) sum_p f(p) y_l^m(p)
// (healpy's map2alm without ring weights), then `iterations` Jacobi steps f_lm += analysis of
// (map - synthesis of f_lm) (healpy's iter). A map of bands < N comes back to the quadrature's
// accuracy, better with each step while the bands stay well below 2 Nside (docs/frames.md).
// Deterministic for any thread count. Cost: (1 + 2 iterations) (N_pix N + rings N^2).
// Throws std::invalid_argument for an order outside 1..runtime::kMaxProjectionOrder or a pixel
// count that is not 12 nside^2.
std::vector<double> analyze_map(std::int64_t nside, const std::vector<double>& ring, int order, int iterations,
                                int threads = 0, const Checkpoint& checkpoint = {});

// The RING map of coefficients of order N: f(p) = sum f_lm y_l^m(p) at every pixel centre. Cost:
// N_pix N + rings N^2.
std::vector<double> synthesize_map(std::int64_t nside, const std::vector<double>& sh, int threads = 0,
                                   const Checkpoint& checkpoint = {});

}  // namespace zhf::healpix
