#include "zhf/healpix/maps.h"

#include <healpix_base.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "zhf/runtime/limits.h"
#include "zhf/runtime/parallel.h"
#include "zhf/runtime/sh_eval.h"

namespace zhf::healpix {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Rings handed to the threads between two checkpoints.
constexpr int kRingsPerBatch = 64;

Healpix_Base2 base(std::int64_t nside, HealpixOrdering ordering) {
  return Healpix_Base2(nside, ordering == HealpixOrdering::kRing ? RING : NEST, SET_NSIDE);
}

void check_nside(std::int64_t nside, std::size_t pixels) {
  if (nside < 1 || nside > kMaxHealpixNside) throw std::invalid_argument("Nside " + std::to_string(nside) + " is outside 1.." + std::to_string(kMaxHealpixNside));
  if (static_cast<std::int64_t>(pixels) != healpix_pixels(nside))
    throw std::invalid_argument(std::to_string(pixels) + " pixels are not 12 Nside^2 (Nside " + std::to_string(nside) + ")");
}

void check_order(int order) {
  if (order < 1 || order > runtime::kMaxProjectionOrder)
    throw std::invalid_argument("order " + std::to_string(order) + " is outside 1.." + std::to_string(runtime::kMaxProjectionOrder));
}

// One ring: its first pixel (RING numbering), pixel count, the Legendre factors y_l^m(theta, 0) of
// bands < N (index(l, m), m >= 0; y_l^-m(theta, phi) = y_l^m(theta, 0) sin(m phi)) and its pixels'
// cos(m phi), sin(m phi) for m < N, pixel-major.
struct Ring {
  std::int64_t first = 0, count = 0;
  std::vector<double> legendre, cosines, sines;
};

Ring ring_at(const Healpix_Base2& geometry, std::int64_t ring, int order) {
  Ring r;
  double theta = 0;
  bool shifted = false;
  geometry.get_ring_info2(ring, r.first, r.count, theta, shifted);
  r.legendre.resize(static_cast<std::size_t>(order) * order);
  const double dir[3] = {std::sin(theta), 0.0, std::cos(theta)};
  runtime::eval_sh(order, dir, r.legendre.data());
  r.cosines.resize(static_cast<std::size_t>(r.count) * order);
  r.sines.resize(r.cosines.size());
  for (std::int64_t j = 0; j < r.count; ++j) {
    const double phi = (static_cast<double>(j) + (shifted ? 0.5 : 0.0)) * 2 * kPi / static_cast<double>(r.count);
    for (int m = 0; m < order; ++m) {
      r.cosines[j * order + m] = std::cos(m * phi);
      r.sines[j * order + m] = std::sin(m * phi);
    }
  }
  return r;
}

// Runs work(ring index 1..4 nside - 1, its Ring, its slot in the batch) on the threads, batch by
// batch; after each batch, done(first ring, rings in it); the checkpoint before each batch.
template <class Work, class Done>
void for_each_ring(std::int64_t nside, int order, int threads, const Checkpoint& checkpoint, Work&& work, Done&& done) {
  const Healpix_Base2 geometry = base(nside, HealpixOrdering::kRing);
  const std::int64_t rings = 4 * nside - 1;
  for (std::int64_t first = 1; first <= rings; first += kRingsPerBatch) {
    if (checkpoint) checkpoint();
    const int batch = static_cast<int>(std::min<std::int64_t>(kRingsPerBatch, rings - first + 1));
    runtime::parallel_for(batch, runtime::worker_count(threads), [&](int b) { work(first + b, ring_at(geometry, first + b, order), b); });
    done(batch);
  }
}

// Sums over each ring's pixels, (4 pi / N_pix) sum_j f_j (cos m phi_j, sin m phi_j), times the
// Legendre columns; rings are added in ring order whatever the thread count.
std::vector<double> analysis_pass(std::int64_t nside, const std::vector<double>& ring_values, int order, int threads,
                                  const Checkpoint& checkpoint) {
  const std::size_t n = static_cast<std::size_t>(order) * order;
  std::vector<double> per_ring(kRingsPerBatch * n), sh(n, 0.0);
  const double weight = 4 * kPi / static_cast<double>(healpix_pixels(nside));
  auto work = [&](std::int64_t, const Ring& r, int slot) {
    std::vector<double> c(order, 0.0), s(order, 0.0);
    for (std::int64_t j = 0; j < r.count; ++j) {
      const double f = ring_values[r.first + j];
      for (int m = 0; m < order; ++m) c[m] += f * r.cosines[j * order + m], s[m] += f * r.sines[j * order + m];
    }
    double* out = per_ring.data() + slot * n;
    for (int l = 0; l < order; ++l) {
      out[runtime::index(l, 0)] = weight * r.legendre[runtime::index(l, 0)] * c[0];
      for (int m = 1; m <= l; ++m) {
        out[runtime::index(l, m)] = weight * r.legendre[runtime::index(l, m)] * c[m];
        out[runtime::index(l, -m)] = weight * r.legendre[runtime::index(l, m)] * s[m];
      }
    }
  };
  auto add = [&](int batch) {
    for (int b = 0; b < batch; ++b)
      for (std::size_t i = 0; i < n; ++i) sh[i] += per_ring[b * n + i];
  };
  for_each_ring(nside, order, threads, checkpoint, work, add);
  return sh;
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

Point pixel_centre(std::int64_t nside, std::int64_t ring_pixel) {
  const vec3 v = base(nside, HealpixOrdering::kRing).pix2vec(ring_pixel);
  return {v.x, v.y, v.z};
}

std::int64_t pixel_at(std::int64_t nside, const Point& direction) {
  return base(nside, HealpixOrdering::kRing).vec2pix(vec3(direction[0], direction[1], direction[2]));
}

std::vector<double> analyze_map(std::int64_t nside, const std::vector<double>& ring, int order, int iterations, int threads,
                                const Checkpoint& checkpoint) {
  check_nside(nside, ring.size());
  check_order(order);
  if (iterations < 0 || iterations > runtime::kMaxHealpixIterations)
    throw std::invalid_argument("iterations " + std::to_string(iterations) + " is outside 0.." + std::to_string(runtime::kMaxHealpixIterations));
  std::vector<double> sh = analysis_pass(nside, ring, order, threads, checkpoint);
  for (int k = 0; k < iterations; ++k) {
    std::vector<double> residual = synthesize_map(nside, sh, threads, checkpoint);
    for (std::size_t p = 0; p < residual.size(); ++p) residual[p] = ring[p] - residual[p];
    const std::vector<double> step = analysis_pass(nside, residual, order, threads, checkpoint);
    for (std::size_t i = 0; i < sh.size(); ++i) sh[i] += step[i];
  }
  return sh;
}

std::vector<double> synthesize_map(std::int64_t nside, const std::vector<double>& sh, int threads, const Checkpoint& checkpoint) {
  const int order = static_cast<int>(std::lround(std::sqrt(static_cast<double>(sh.size()))));
  if (static_cast<std::size_t>(order) * order != sh.size() || order < 1)
    throw std::invalid_argument(std::to_string(sh.size()) + " coefficients are not N^2 for an order N");
  check_order(order);
  if (nside < 1 || nside > kMaxHealpixNside) throw std::invalid_argument("Nside " + std::to_string(nside) + " is outside 1.." + std::to_string(kMaxHealpixNside));
  std::vector<double> map(static_cast<std::size_t>(healpix_pixels(nside)));
  auto work = [&](std::int64_t, const Ring& r, int) {
    std::vector<double> a(order, 0.0), b(order, 0.0);
    for (int l = 0; l < order; ++l) {
      a[0] += sh[runtime::index(l, 0)] * r.legendre[runtime::index(l, 0)];
      for (int m = 1; m <= l; ++m) {
        a[m] += sh[runtime::index(l, m)] * r.legendre[runtime::index(l, m)];
        b[m] += sh[runtime::index(l, -m)] * r.legendre[runtime::index(l, m)];
      }
    }
    for (std::int64_t j = 0; j < r.count; ++j) {
      double f = a[0];
      for (int m = 1; m < order; ++m) f += a[m] * r.cosines[j * order + m] + b[m] * r.sines[j * order + m];
      map[r.first + j] = f;
    }
  };
  for_each_ring(nside, order, threads, checkpoint, work, [](int) {});
  return map;
}

}  // namespace zhf::healpix
