#include "zhf/healpix/maps.h"

#include <alm_healpix_tools.h>
#include <healpix_base.h>
#include <healpix_map.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "zhf/healpix/alm.h"
#include "zhf/healpix/limits.h"
#include "zhf/runtime/errors.h"
#include "zhf/runtime/sh_eval.h"

namespace zhf::healpix {
namespace {


Healpix_Base2 base(std::int64_t nside, HealpixOrdering ordering) {
  return Healpix_Base2(nside, ordering == HealpixOrdering::kRing ? RING : NEST, SET_NSIDE);
}

void check_nside(std::int64_t nside, std::size_t pixels) {
  if (nside < 1 || nside > kMaxHealpixNside) throw std::invalid_argument("Nside " + std::to_string(nside) + " is outside 1.." + std::to_string(kMaxHealpixNside));
  if (static_cast<std::int64_t>(pixels) != healpix_pixels(nside))
    throw std::invalid_argument(std::to_string(pixels) + " pixels are not 12 Nside^2 (Nside " + std::to_string(nside) + ")");
}

void check_order(int order) {
  if (order < 1 || order > runtime::kMaxShOrder)
    throw std::invalid_argument("order " + std::to_string(order) + " is outside 1.." + std::to_string(runtime::kMaxShOrder));
}

Healpix_Map<double> ring_map(std::int64_t nside, const std::vector<double>& ring) {
  Healpix_Map<double> map(static_cast<int>(nside), RING, SET_NSIDE);
  for (std::size_t p = 0; p < ring.size(); ++p) map[static_cast<int>(p)] = ring[p];
  return map;
}

}  // namespace

std::vector<double> ring_pixels(const HealpixMap& map) {
  check_nside(map.nside, map.pixels.size());
  if (map.ordering == HealpixOrdering::kRing) return map.pixels;
  const Healpix_Base2 geometry = base(map.nside, HealpixOrdering::kNested);
  std::vector<double> ring(map.pixels.size());
  for (std::int64_t p = 0; p < static_cast<std::int64_t>(ring.size()); ++p) ring[geometry.nest2ring(p)] = map.pixels[p];
  return ring;
}

HealpixMap map_from_ring(std::int64_t nside, std::vector<double> ring, HealpixOrdering ordering) {
  check_nside(nside, ring.size());
  HealpixMap map;
  map.nside = nside;
  map.ordering = ordering;
  if (ordering == HealpixOrdering::kRing) {
    map.pixels = std::move(ring);
    return map;
  }
  if ((nside & (nside - 1)) != 0) throw std::invalid_argument("Nside " + std::to_string(nside) + " is not a power of two, as NESTED ordering needs");
  const Healpix_Base2 geometry = base(nside, HealpixOrdering::kNested);
  map.pixels.resize(ring.size());
  for (std::int64_t p = 0; p < static_cast<std::int64_t>(ring.size()); ++p) map.pixels[p] = ring[geometry.nest2ring(p)];
  return map;
}

MaskedSignal masked_signal(const HealpixMap& map, const std::string& map_name, const HealpixMap* mask, const std::string& mask_name) {
  MaskedSignal signal;
  signal.nside = map.nside;
  signal.ring = ring_pixels(map);
  if (!mask) {
    if (map.unseen > 0)
      throw runtime::InputError(map_name + ": " + std::to_string(map.unseen) + " UNSEEN pixels (the first: pixel " + std::to_string(map.first_unseen) +
                                ") and no mask to cover them (--mask)");
    return signal;
  }
  if (mask->nside != map.nside)
    throw runtime::InputError(mask_name + ": NSIDE " + std::to_string(mask->nside) + " is not the map's " + std::to_string(map.nside));
  signal.weights = ring_pixels(*mask);
  const std::vector<double>& weights = signal.weights;
  double sum = 0;
  for (std::size_t p = 0; p < weights.size(); ++p) {
    if (!(weights[p] >= 0 && weights[p] <= 1))
      throw runtime::InputError(mask_name + ": pixel " + std::to_string(p) + " (RING) is " + runtime::format_number(weights[p]) + ", outside [0, 1]");
    if (is_unseen(signal.ring[p]) && weights[p] != 0)
      throw runtime::InputError(map_name + ": pixel " + std::to_string(p) + " (RING) is UNSEEN where the mask keeps it (" + runtime::format_number(weights[p]) + ")");
    signal.ring[p] = weights[p] == 0 ? 0.0 : signal.ring[p] * weights[p];
    sum += weights[p];
  }
  signal.sky_fraction = sum / static_cast<double>(weights.size());
  return signal;
}

MaskedSignal read_masked_signal(const std::string& map_path, const std::string& mask_path) {
  const HealpixMap map = read_healpix_map(map_path);
  if (mask_path.empty()) return masked_signal(map, map_path, nullptr, mask_path);
  const HealpixMap mask = read_healpix_map(mask_path);
  return masked_signal(map, map_path, &mask, mask_path);
}

Point pixel_centre(std::int64_t nside, std::int64_t ring_pixel) {
  const vec3 v = base(nside, HealpixOrdering::kRing).pix2vec(ring_pixel);
  return {v.x, v.y, v.z};
}

std::int64_t pixel_at(std::int64_t nside, const Point& direction) {
  return base(nside, HealpixOrdering::kRing).vec2pix(vec3(direction[0], direction[1], direction[2]));
}

std::vector<double> analyze_map(std::int64_t nside, const std::vector<double>& ring, int order, int iterations, const Checkpoint& checkpoint) {
  check_nside(nside, ring.size());
  check_order(order);
  if (order - 1 > max_analysis_band(nside))
    throw std::invalid_argument("band " + std::to_string(order - 1) + " is above 4 Nside = " + std::to_string(max_analysis_band(nside)) + ", what the map's rings resolve");
  if (iterations < 0 || iterations > healpix::kMaxHealpixIterations)
    throw std::invalid_argument("iterations " + std::to_string(iterations) + " is outside 0.." + std::to_string(healpix::kMaxHealpixIterations));
  const Healpix_Map<double> map = ring_map(nside, ring);
  const arr<double> unit_weights(2 * static_cast<std::size_t>(nside), 1.0);
  ComplexAlm alm(order - 1, order - 1);
  if (checkpoint) checkpoint();
  map2alm(map, alm, unit_weights, false);
  Healpix_Map<double> residual(static_cast<int>(nside), RING, SET_NSIDE);
  for (int k = 0; k < iterations; ++k) {
    if (checkpoint) checkpoint();
    alm2map(alm, residual);
    for (int p = 0; p < map.Npix(); ++p) residual[p] = map[p] - residual[p];
    if (checkpoint) checkpoint();
    map2alm(residual, alm, unit_weights, true);
  }
  std::vector<double> f(static_cast<std::size_t>(order) * order);
  alm_to_real(alm, f.data());
  return f;
}

std::vector<double> synthesize_map(std::int64_t nside, const std::vector<double>& sh, const Checkpoint& checkpoint) {
  const int order = static_cast<int>(std::lround(std::sqrt(static_cast<double>(sh.size()))));
  if (order < 1 || static_cast<std::size_t>(order) * order != sh.size())
    throw std::invalid_argument(std::to_string(sh.size()) + " coefficients are not N^2 for an order N");
  check_order(order);
  if (nside < 1 || nside > kMaxHealpixNside) throw std::invalid_argument("Nside " + std::to_string(nside) + " is outside 1.." + std::to_string(kMaxHealpixNside));
  if (checkpoint) checkpoint();
  Healpix_Map<double> map(static_cast<int>(nside), RING, SET_NSIDE);
  ComplexAlm alm(order - 1, order - 1);
  real_to_alm(sh.data(), alm);
  alm2map(alm, map);
  return std::vector<double>(&map[0], &map[0] + map.Npix());
}

}  // namespace zhf::healpix
