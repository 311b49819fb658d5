#include "palette.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "zhf/io/signals.h"
#include "zhf/runtime/parallel.h"
#include "zhf/sh/random.h"
#include "zhf/splat/limits.h"

namespace zhf::splat {
namespace {

// Lloyd steps of each k-means, and the points the first level is fitted on (every
// count / kPaletteSample-th): fixed, so the work is bounded by the count.
constexpr int kPaletteSteps = 8;
constexpr std::size_t kPaletteSample = 1 << 16;

// Centroids a distance pass compares at once: each lane sums its own squares, so the compiler
// vectorises across centroids without reordering any sum.
constexpr int kLanes = 8;

// k centroids of dim values, in blocks of kLanes laid out [block][d][lane]; unused lanes far away.
class Centroids {
 public:
  Centroids(int k, int dim) : k_(k), dim_(dim), blocks_((k + kLanes - 1) / kLanes), values_(std::size_t(blocks_) * dim * kLanes, kFar) {}
  void set(int c, const float* v) {
    for (int d = 0; d < dim_; ++d) values_[(std::size_t(c / kLanes) * dim_ + d) * kLanes + c % kLanes] = v[d];
  }
  float get(int c, int d) const { return values_[(std::size_t(c / kLanes) * dim_ + d) * kLanes + c % kLanes]; }
  // The nearest centroid to p and its squared distance (ties: the lower index).
  std::pair<int, float> nearest(const float* p) const {
    int best = 0;
    float best_distance = std::numeric_limits<float>::infinity();
    for (int b = 0; b < blocks_; ++b) {
      float sums[kLanes] = {};
      const float* block = &values_[std::size_t(b) * dim_ * kLanes];
      for (int d = 0; d < dim_; ++d)
        for (int j = 0; j < kLanes; ++j) {
          const float diff = p[d] - block[d * kLanes + j];
          sums[j] += diff * diff;
        }
      for (int j = 0; j < kLanes && b * kLanes + j < k_; ++j)
        if (sums[j] < best_distance) {
          best_distance = sums[j];
          best = b * kLanes + j;
        }
    }
    return {best, best_distance};
  }
  int size() const { return k_; }

 private:
  static constexpr float kFar = 1e30f;
  int k_, dim_, blocks_;
  std::vector<float> values_;
};

// Lloyd's k-means of the points `members` (indices into points, ascending) into k centroids,
// started from k of them drawn by rng; labels[i] is member i's centroid. Its assignment spread
// over `threads`; the update summed in member order.
Centroids lloyd(const float* points, std::size_t stride, int dim, const std::vector<std::uint32_t>& members, int k, sh::Rng& rng, int threads,
                std::vector<std::uint32_t>& labels) {
  const std::size_t m = members.size();
  labels.assign(m, 0);
  Centroids centroids(k, dim);
  // k distinct members: a partial Fisher-Yates shuffle of their positions.
  std::vector<std::uint32_t> order(m);
  std::iota(order.begin(), order.end(), 0u);
  for (int c = 0; c < k; ++c) {
    const std::size_t pick = std::size_t(c) + std::size_t(sh::uniform01(rng) * double(m - std::size_t(c)));
    std::swap(order[c], order[std::min(pick, m - 1)]);
    centroids.set(c, points + std::size_t(members[order[c]]) * stride);
  }
  std::vector<float> distance(m);
  std::vector<double> sums(std::size_t(k) * dim);
  std::vector<std::size_t> counts(k);
  for (int step = 0; step <= kPaletteSteps; ++step) {
    runtime::parallel_chunks(m, threads, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        const auto [c, d] = centroids.nearest(points + std::size_t(members[i]) * stride);
        labels[i] = std::uint32_t(c);
        distance[i] = d;
      }
    });
    if (step == kPaletteSteps) break;  // the last assignment is to the final centroids
    std::fill(sums.begin(), sums.end(), 0.0);
    std::fill(counts.begin(), counts.end(), 0);
    for (std::size_t i = 0; i < m; ++i) {
      const std::uint32_t c = labels[i];
      const float* p = points + std::size_t(members[i]) * stride;
      for (int d = 0; d < dim; ++d) sums[std::size_t(c) * dim + d] += p[d];
      ++counts[c];
    }
    std::vector<float> mean(dim);
    for (int c = 0; c < k; ++c) {
      if (counts[c] == 0) {
        // An empty centroid moves to the member farthest from its own (the lowest such).
        const std::size_t far = std::size_t(std::max_element(distance.begin(), distance.end()) - distance.begin());
        distance[far] = 0;
        centroids.set(c, points + std::size_t(members[far]) * stride);
        continue;
      }
      for (int d = 0; d < dim; ++d) mean[d] = float(sums[std::size_t(c) * dim + d] / double(counts[c]));
      centroids.set(c, mean.data());
    }
    io::throw_if_interrupted();
  }
  return centroids;
}

}  // namespace

Palette fit_palette(const float* points, std::size_t stride, std::size_t count, int dim, int max_entries, std::uint64_t seed, int threads) {
  Palette palette;
  palette.labels.resize(count);
  if (count <= std::size_t(max_entries)) {
    for (std::size_t i = 0; i < count; ++i) palette.entries.insert(palette.entries.end(), points + i * stride, points + i * stride + dim);
    std::iota(palette.labels.begin(), palette.labels.end(), 0u);
    return palette;
  }
  // Level one: sqrt(max_entries) clusters, fitted on a sample, then every point's nearest.
  sh::Rng rng(seed);
  const int clusters = std::max(1, int(std::sqrt(double(max_entries))));
  std::vector<std::uint32_t> sample;
  const std::size_t every = std::max<std::size_t>(1, count / kPaletteSample);
  for (std::size_t i = 0; i < count; i += every) sample.push_back(std::uint32_t(i));
  std::vector<std::uint32_t> sample_labels, cluster(count);
  const Centroids top = lloyd(points, stride, dim, sample, clusters, rng, threads, sample_labels);
  runtime::parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) cluster[i] = std::uint32_t(top.nearest(points + i * stride).first);
  });
  // Level two: each cluster's share of the entries (at least one, at most its points, at most
  // max_entries together; the remainder by the largest fractions, then the lower cluster).
  std::vector<std::vector<std::uint32_t>> members(clusters);
  for (std::size_t i = 0; i < count; ++i) members[cluster[i]].push_back(std::uint32_t(i));
  std::vector<int> share(clusters, 0);
  std::vector<std::pair<double, int>> remainders;
  int given = 0;
  for (int c = 0; c < clusters; ++c) {
    if (members[c].empty()) continue;
    const double exact = double(max_entries) * double(members[c].size()) / double(count);
    share[c] = int(std::min<double>(std::max(1.0, std::floor(exact)), double(members[c].size())));
    given += share[c];
    remainders.push_back({exact - std::floor(exact), c});
  }
  // The one-entry floor can overshoot: the largest shares (the lower cluster first) give back.
  while (given > max_entries) {
    --*std::max_element(share.begin(), share.end());
    --given;
  }
  std::stable_sort(remainders.begin(), remainders.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t r = 0; given < max_entries && r < remainders.size(); ++r) {
    const int c = remainders[r].second;
    if (std::size_t(share[c]) < members[c].size()) {
      ++share[c];
      ++given;
    }
  }
  std::vector<int> first(clusters + 1, 0);
  for (int c = 0; c < clusters; ++c) first[c + 1] = first[c] + share[c];
  palette.entries.assign(std::size_t(first[clusters]) * dim, 0.0f);
  // Each cluster on one thread, its draws from a generator of its own: no order shows.
  runtime::parallel_for(clusters, runtime::worker_count(threads), [&](int c) {
    if (members[c].empty()) return;
    sh::Rng own(seed ^ (0x9e3779b97f4a7c15ull * std::uint64_t(c + 1)));
    std::vector<std::uint32_t> labels;
    const Centroids part = lloyd(points, stride, dim, members[c], share[c], own, 1, labels);
    for (int e = 0; e < share[c]; ++e)
      for (int d = 0; d < dim; ++d) palette.entries[std::size_t(first[c] + e) * dim + d] = part.get(e, d);
    for (std::size_t i = 0; i < members[c].size(); ++i) palette.labels[members[c][i]] = std::uint32_t(first[c]) + labels[i];
  });
  return palette;
}

}  // namespace zhf::splat
