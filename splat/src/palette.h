// A palette of at most `max_entries` vectors for many points, and each point's entry: what a SOG
// stores of the SH above band 0. k-means in two levels, so that 10^6 points and 65 536 entries
// take seconds: about sqrt(max_entries) clusters over a sample of the points, every point given
// its nearest, then each cluster's points split by k-means of their own into a share of the
// entries proportional to the cluster's size. Squared Euclidean distance in float; a fixed number
// of Lloyd steps; ties to the lower index. The same points, seed and entries give the same
// palette whatever the thread count. count <= max_entries: each point is its own entry (exact).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace zhf::splat {

struct Palette {
  std::vector<float> entries;        // entry-major, dim values each
  std::vector<std::uint32_t> labels;  // per point
};

// Point i's dim values at points + i * stride.
Palette fit_palette(const float* points, std::size_t stride, std::size_t count, int dim, int max_entries, std::uint64_t seed, int threads);

}  // namespace zhf::splat
