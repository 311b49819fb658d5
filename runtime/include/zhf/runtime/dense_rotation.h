// DenseRotation: the band matrices of one rotation, built once (Rotator::dense, about the cost of
// N^2 single rotations) and applied to many vectors: one at a time, 3D Gaussian Splatting's
// interleaved RGB layout, or planar arrays. Convention as Rotator: out_l = D_l in_l.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <utility>
#include <vector>

#include "zhf/runtime/limits.h"
#include "zhf/runtime/pack.h"
#include "zhf/runtime/parallel.h"
#include "zhf/runtime/sh_eval.h"

// The bodies of the unrolled loops below (for_each_index) are inlined: GCC's flatten does it for
// the function that holds them, Clang's does not reach into lambdas (under Emscripten the order-4
// splats ran 2x slower with each band's loop a call). Only when optimising: at -O0 (the sanitized
// runtime tests) forced inlining buys nothing and doubles clang's compile time (transforms_test's
// unit under ASan: 88 s with it, 44 s without).
#if defined(__GNUC__) && defined(__OPTIMIZE__)
#define ZHF_UNROLLED __attribute__((always_inline))
#define ZHF_FLATTEN __attribute__((flatten))
#else
#define ZHF_UNROLLED
#define ZHF_FLATTEN
#endif

namespace zhf::runtime {

// Build-once, apply-many band matrices of one rotation.
template <class T>
class DenseRotation {
 public:
  DenseRotation(int order, std::vector<std::vector<T>> bands) : order_(order), bands_(std::move(bands)) {
    // apply() runs column by column: out_l += column j of D_l times in_l[j], a loop over
    // contiguous rows that vectorises, so it keeps the transposes.
    for (int l = 0; l < order_; ++l) {
      const int n = band_size(l);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) columns_.push_back(bands_[l][i * n + j]);
    }
    // The bands above 0 as one block-diagonal matrix cut into packs of output rows: each pack is
    // a sum of the columns of the inputs whose band has rows in it.
    const int rest = order_ * order_ - 1;
    rest_packs_ = (rest + P::kLanes - 1) / P::kLanes;
    for (int p = 0; p < rest_packs_; ++p) {
      rest_pack_begin_.push_back(static_cast<int>(rest_columns_.size()));
      const int start = rest_pack_row(p, rest);
      for (int l = 1; l < order_; ++l) {
        if (!band_in_pack(l, start)) continue;
        const int n = band_size(l), first_row = l * l - 1;
        for (int j = 0; j < n; ++j) {
          T lanes[P::kLanes] = {};
          for (int k = 0; k < P::kLanes; ++k) {
            const int row = start + k - first_row;
            if (row >= 0 && row < n) lanes[k] = bands_[l][row * n + j];
          }
          rest_columns_.push_back(P::load(lanes));
          rest_inputs_.push_back(first_row + j);
        }
      }
    }
    rest_pack_begin_.push_back(static_cast<int>(rest_columns_.size()));
  }

  int order() const { return order_; }
  int coefficients() const { return order_ * order_; }
  // bands()[l] is (2l+1)^2 row-major: out_l = D_l in_l.
  const std::vector<std::vector<T>>& bands() const { return bands_; }
  // out = D in for one vector of N^2 (in and out must not overlap). Cost: sum (2l+1)^2
  // multiply-adds, with fixed band sizes for the generated orders and packs of rows above.
  void apply(const T* in, T* out) const {
    switch (order_) {
      case 1: return apply_bands<1>(in, out);
      case 2: return apply_bands<2>(in, out);
      case 3: return apply_bands<3>(in, out);
      case 4: return apply_bands<4>(in, out);
      case 5: return apply_bands<5>(in, out);
      case 6: return apply_bands<6>(in, out);
      case 7: return apply_bands<7>(in, out);
      case 8: return apply_bands<8>(in, out);
      default: break;
    }
    out[0] = in[0];
    apply_rest(in + 1, out + 1);
  }

  // 3D Gaussian Splatting's layout, count items of 3 N^2 values: the three band-0 values (R, G,
  // B), then bands 1.. of R, of G and of B (N^2 - 1 each). in == out is allowed. Cost per item:
  // 3 sum_{l>0} (2l+1) x (packs of rows band l touches) pack multiply-adds (N = 4: 45 for 249
  // scalar multiply-adds; N = 8: 333 for 2040), straight-line code at orders 3..8;
  // docs/performance.md compares it with memory bandwidth.
  void apply_splats(std::size_t count, const T* in, T* out, int threads = 0) const {
    switch (order_) {
      case 2: return apply_splats_of<2>(count, in, out, threads);
      case 3: return apply_splats_of<3>(count, in, out, threads);
      case 4: return apply_splats_of<4>(count, in, out, threads);
      case 5: return apply_splats_of<5>(count, in, out, threads);
      case 6: return apply_splats_of<6>(count, in, out, threads);
      case 7: return apply_splats_of<7>(count, in, out, threads);
      case 8: return apply_splats_of<8>(count, in, out, threads);
      default: return apply_splats_of<0>(count, in, out, threads);
    }
  }

  // Planar layout: plane p = c N^2 + i holds coefficient i of channel c of every item,
  // in[p count + v], for channels planes sets. in == out is allowed. A block of items at a time,
  // band by band, a cache line of items per step: 2 (2l + 1) planes are read and written at once,
  // in runs of the block's length; large outputs are stored past the caches (planar_streams).
  // The same multiply-adds as apply() per item, so the same results whichever way it stores.
  void apply_planar(std::size_t count, int channels, const T* in, T* out, int threads = 0) const {
    const bool streamed = planar_streams(count, channels, in, out);
    parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
      for (std::size_t block = begin; block < end; block += kPlanarBlock) {
        const std::size_t block_end = std::min(end, block + kPlanarBlock);
        for (int c = 0; c < channels; ++c) {
          const std::size_t first_plane = static_cast<std::size_t>(c) * static_cast<std::size_t>(coefficients());
          const T* f = in + first_plane * count;
          T* g = out + first_plane * count;
          for (std::size_t v = block; v < block_end; ++v) g[v] = f[v];  // band 0
          const T* d = columns_.data() + 1;
          for (int l = 1; l < order_; ++l) {
            const std::size_t first_row = static_cast<std::size_t>(l * l) * count;
            // Single items up to a cache-line boundary of the band's first plane, then a whole
            // line of every plane per step (when planes are a multiple of a line apart, as with
            // counts that are powers of two, they share cache sets, and a line used half by one
            // step was evicted before the next: order 8 ran at 35 % of the copy, one thread),
            // then packs and single items for the rest.
            std::size_t v = block;
            for (; v < block_end && reinterpret_cast<std::uintptr_t>(f + first_row + v) % kCacheLineBytes; ++v)
              apply_planar_band<T>(l, d, f + first_row + v, g + first_row + v, count);
            for (; v + Line::kLanes <= block_end; v += Line::kLanes) {
              if (streamed) apply_planar_band<Line, true>(l, d, f + first_row + v, g + first_row + v, count);
              else apply_planar_band<Line>(l, d, f + first_row + v, g + first_row + v, count);
            }
            for (; v + P::kLanes <= block_end; v += P::kLanes)
              apply_planar_band<P>(l, d, f + first_row + v, g + first_row + v, count);
            for (; v < block_end; ++v)
              apply_planar_band<T>(l, d, f + first_row + v, g + first_row + v, count);
            d += band_size(l) * band_size(l);
          }
        }
      }
      if (streamed) stream_fence();
    });
  }

  // Whether apply_planar with these arguments stores its whole-line steps past the caches: out of
  // place, outputs of kStreamedOutputBytes or more, planes a whole number of cache lines apart
  // (count a multiple of 16 floats or 8 doubles) and out a whole number of lines from in, so that
  // every such step writes whole lines of every plane of out (a line written in two steps could
  // leave the write-combining buffer in halves).
  bool planar_streams(std::size_t count, int channels, const T* in, const T* out) const {
    const std::size_t planes = std::size_t(channels) * std::size_t(coefficients());
    return in != out && planes > 0 && count >= kStreamedOutputBytes / sizeof(T) / planes &&
           count % (kCacheLineBytes / sizeof(T)) == 0 &&
           (reinterpret_cast<std::uintptr_t>(out) - reinterpret_cast<std::uintptr_t>(in)) % kCacheLineBytes == 0;
  }

 private:
  using P = Pack<T, kBulkPackBytes>;
  using Line = Pack<T, kCacheLineBytes>;  // a cache line of items: two AVX2 registers
  // apply_planar's items per block: long runs per plane for the prefetchers (2048 and more
  // measured alike; 256 ran 1.6x slower at order 4), the band's planes within L2.
  static constexpr std::size_t kPlanarBlock = 4096;
  // Outputs at least this large (twice a 32 MiB L3) are not read back from the caches, so
  // apply_planar writes them without the reads a cached store makes first (AMD Zen 4, planar
  // out of place: 1.2x to 1.5x faster at 50 MiB and up; mixed at 12 to 25 MiB). apply_splats
  // keeps cached stores: streamed through a buffer of whole lines its order-8 outputs ran 1.02x
  // to 1.35x faster in most runs and 2x slower in others (the one output stream right behind the
  // one input stream, as if the two collided in memory).
  static constexpr std::size_t kStreamedOutputBytes = std::size_t(64) << 20;
  // Splats apply_splats rotates per step at order N: two in WebAssembly up to order 5 (the 3DGS
  // degrees the files carry), where a column pack loaded once for six channels beat once for three
  // (order 4, Node 20, in cache: 26 to 28 ns a splat against 30 to 31); one elsewhere.
#if defined(__wasm_simd128__)
  static constexpr std::size_t splats_per_step(int order) { return order <= 5 ? 2 : 1; }
#else
  static constexpr std::size_t splats_per_step(int) { return 1; }
#endif

  // Bands 1.. are cut into packs of kLanes output rows. Pack p starts at row p kLanes, except
  // that the last one ends at the last row, overlapping its neighbour, so that every pack is
  // stored whole inside the vector (rest < kLanes: one pack, stored lane by lane).
  static constexpr int rest_pack_row(int p, int rest) { return std::max(0, std::min(p * P::kLanes, rest - P::kLanes)); }
  // Whether band l has rows in the pack starting at row start.
  static constexpr bool band_in_pack(int l, int start) {
    const int first_row = l * l - 1;
    return first_row < start + P::kLanes && first_row + band_size(l) > start;
  }

  // apply_splats with the order fixed (N > 0) or read at run time (N = 0).
  template <int N>
  void apply_splats_of(std::size_t count, const T* in, T* out, int threads) const {
    const std::size_t rest = static_cast<std::size_t>(coefficients() - 1), item = 3 + 3 * rest;
    parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
      std::size_t v = begin;
      constexpr std::size_t kStep = splats_per_step(N);
      if constexpr (N > 2 && kStep > 1) {
        for (; v + kStep <= end; v += kStep) {
          for (std::size_t k = 0; k < kStep; ++k)
            for (int c = 0; c < 3; ++c) out[item * (v + k) + c] = in[item * (v + k) + c];
          apply_splat_rest<N, kStep>(in + item * v + 3, out + item * v + 3);
        }
      }
      for (; v < end; ++v) {
        const T* f = in + item * v;
        T* g = out + item * v;
        for (int c = 0; c < 3; ++c) g[c] = f[c];
        if constexpr (N == 2) {
          for (int c = 0; c < 3; ++c) apply_band1(f + 3 + c * rest, g + 3 + c * rest);
        } else if constexpr (N > 0) {
          apply_splat_rest<N, 1>(f + 3, g + 3);
        } else {
          for (int c = 0; c < 3; ++c) apply_rest(f + 3 + c * rest, g + 3 + c * rest);
        }
      }
    });
  }

  // y = D x over bands 1.. (N^2 - 1 values each); x may be y (every pack is formed before any
  // is stored).
  void apply_rest(const T* x, T* y) const {
    P acc[(kMaxZxzxzOrder * kMaxZxzxzOrder + P::kLanes - 1) / P::kLanes];  // any Rotator's order
    for (int p = 0; p < rest_packs_; ++p) {
      // Four partial sums: one would be a chain of dependent multiply-adds.
      P sum[4] = {P(0.0), P(0.0), P(0.0), P(0.0)};
      const P* column = &rest_columns_[rest_pack_begin_[p]];
      const int* input = &rest_inputs_[rest_pack_begin_[p]];
      const int terms = rest_pack_begin_[p + 1] - rest_pack_begin_[p];
      int t = 0;
      for (; t + 4 <= terms; t += 4)
        for (int k = 0; k < 4; ++k) sum[k] += column[t + k] * P::broadcast(x[input[t + k]]);
      for (; t < terms; ++t) sum[t % 4] += column[t] * P::broadcast(x[input[t]]);
      acc[p] = (sum[0] + sum[1]) + (sum[2] + sum[3]);
    }
    const int rest = coefficients() - 1;
    if (rest >= P::kLanes) {
      for (int p = 0; p < rest_packs_; ++p) acc[p].store(y + rest_pack_row(p, rest));
    } else if (rest > 0) {
      T lanes[P::kLanes];
      acc[0].store(lanes);
      // A few scalar stores: a memcpy of run-time length is a library call.
      for (int k = 0; k < rest; ++k) y[k] = lanes[k];
    }
  }

  // y = D_1 x for band 1 alone (order 2, less than a pack of rows); x may be y.
  void apply_band1(const T* x, T* y) const {
    const T* d = columns_.data() + 1;  // D_1 column-major
    const T x0 = x[0], x1 = x[1], x2 = x[2];
    for (int i = 0; i < 3; ++i) y[i] = d[i] * x0 + d[3 + i] * x1 + d[6 + i] * x2;
  }

  // apply_rest on the three channels of S splats (x: N^2 - 1 values of each channel, one after
  // another, the splats 3 N^2 values apart) at a fixed order of at least one whole pack of rows, as
  // straight-line code: band by band, each input broadcast once for the packs its band has rows in
  // and each column pack loaded once for the 3 S channels; a pack is stored once the last band
  // with rows in it is done, when those rows' inputs have all been read, so x may be y. Each
  // channel's arithmetic is the same whatever S.
  template <int N, int S>
  ZHF_FLATTEN ZHF_UNROLLED void apply_splat_rest(const T* x, T* y) const {
    constexpr int rest = N * N - 1, packs = (rest + P::kLanes - 1) / P::kLanes, item = 3 * N * N;
    static_assert(rest >= P::kLanes, "a whole pack of rows");
    const P* columns = rest_columns_.data();  // a local: the stores could alias the member
    P acc[3 * S][packs];  // each starts at its first term (a product, not 0 plus it)
    for_each_index<N>([&](auto l) ZHF_UNROLLED {
      if constexpr (l > 0) {
        for_each_index<band_size(l)>([&](auto j) ZHF_UNROLLED {
          P input[3 * S];
          for_each_index<3 * S>([&](auto c) ZHF_UNROLLED { input[c] = P::broadcast(x[c / 3 * item + c % 3 * rest + l * l - 1 + j]); });
          for_each_index<packs>([&](auto p) ZHF_UNROLLED {
            if constexpr (band_in_pack(l, rest_pack_row(p, rest))) {
              const P d = columns[column_of(N, p, l) + j];
              if constexpr (j == 0 && first_band_in_pack(rest_pack_row(p, rest)) == l)
                for_each_index<3 * S>([&](auto c) ZHF_UNROLLED { acc[c][p] = d * input[c]; });
              else
                for_each_index<3 * S>([&](auto c) ZHF_UNROLLED { acc[c][p] += d * input[c]; });
            }
          });
        });
        for_each_index<packs>([&](auto p) ZHF_UNROLLED {
          constexpr int start = rest_pack_row(p, rest);
          if constexpr (band_in_pack(l, start) && (l + 1 == N || !band_in_pack(l + 1, start)))
            for_each_index<3 * S>([&](auto c) ZHF_UNROLLED { acc[c][p].store(y + c / 3 * item + c % 3 * rest + start); });
        });
      }
    });
  }
  // The lowest band with rows in the pack starting at row start.
  static constexpr int first_band_in_pack(int start) {
    int l = 1;
    while (!band_in_pack(l, start)) ++l;
    return l;
  }
  // Where band l's first column in pack p sits among the rest columns, at order N.
  static constexpr int column_of(int order, int p, int l) {
    const int rest = order * order - 1;
    int offset = 0;
    for (int q = 0; q <= p; ++q)
      for (int k = 1; k < (q < p ? order : l); ++k)
        if (band_in_pack(k, rest_pack_row(q, rest))) offset += band_size(k);
    return offset;
  }
  // f(std::integral_constant<int, i>) for i = 0 .. Count - 1, unrolled.
  template <int Count, class F>
  ZHF_UNROLLED static void for_each_index(F&& f) {
    for_each_index(f, std::make_integer_sequence<int, Count>());
  }
  template <class F, int... I>
  ZHF_UNROLLED static void for_each_index(F& f, std::integer_sequence<int, I...>) {
    (f(std::integral_constant<int, I>()), ...);
  }

  // Band l of apply_planar (d: D_l column-major) on V (a Pack: kLanes items; T: one item): the
  // band's 2l + 1 planes from in and out, stride apart. Two partial sums per row, in the same
  // order for V = T and V = P, so an item's result does not depend on where a chunk starts; the
  // bands of the generated orders run as straight-line code.
  template <class V, bool kStreamed = false>
  void apply_planar_band(int l, const T* d, const T* in, T* out, std::size_t stride) const {
    switch (l) {
      case 1: return apply_planar_band_of<V, 1, kStreamed>(d, in, out, stride);
      case 2: return apply_planar_band_of<V, 2, kStreamed>(d, in, out, stride);
      case 3: return apply_planar_band_of<V, 3, kStreamed>(d, in, out, stride);
      case 4: return apply_planar_band_of<V, 4, kStreamed>(d, in, out, stride);
      case 5: return apply_planar_band_of<V, 5, kStreamed>(d, in, out, stride);
      case 6: return apply_planar_band_of<V, 6, kStreamed>(d, in, out, stride);
      case 7: return apply_planar_band_of<V, 7, kStreamed>(d, in, out, stride);
      default: break;
    }
    const int n = band_size(l);
    V x[2 * kMaxZxzxzOrder - 1];
    for (int j = 0; j < n; ++j) x[j] = load<V>(in + j * stride);
    for (int i = 0; i < n; ++i) {
      V even(T(0)), odd(T(0));
      for (int j = 0; j + 1 < n; j += 2) {
        even += V(d[j * n + i]) * x[j];
        odd += V(d[(j + 1) * n + i]) * x[j + 1];
      }
      even += V(d[(n - 1) * n + i]) * x[n - 1];
      store_row<kStreamed>(even + odd, out + i * stride);
    }
  }
  template <class V, int L, bool kStreamed>
  [[gnu::flatten]] void apply_planar_band_of(const T* d, const T* in, T* out, std::size_t stride) const {
    constexpr int n = band_size(L);
    V x[n];
    for_each_index<n>([&](auto j) ZHF_UNROLLED { x[j] = load<V>(in + j * stride); });
    for_each_index<n>([&](auto i) ZHF_UNROLLED {
      V even(T(0)), odd(T(0));
      for_each_index<n>([&](auto j) ZHF_UNROLLED { (j % 2 ? odd : even) += V(d[j * n + i]) * x[j]; });
      store_row<kStreamed>(even + odd, out + i * stride);
    });
  }
  template <class V>
  static V load(const T* p) {
    if constexpr (std::is_same_v<V, T>) return *p;
    else return V::load(p);
  }
  static void store(const T& value, T* p) { *p = value; }
  static void store(const P& value, T* p) { value.store(p); }
  static void store(const Line& value, T* p) { value.store(p); }
  // A row of apply_planar_band: past the caches where kStreamed (whole-line steps only).
  template <bool kStreamed, class V>
  static void store_row(const V& value, T* p) {
    if constexpr (kStreamed) value.stream(p);
    else store(value, p);
  }

  template <int N>
  void apply_bands(const T* in, T* out) const {
    apply_band<0, N>(columns_.data(), in, out);
  }
  template <int L, int N>
  static void apply_band(const T* d, const T* in, T* out) {
    if constexpr (L < N) {
      constexpr int n = 2 * L + 1, base = L * L;
      T sum[n] = {};
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) sum[i] += d[j * n + i] * in[base + j];
      for (int i = 0; i < n; ++i) out[base + i] = sum[i];
      apply_band<L + 1, N>(d + n * n, in, out);
    }
  }

  int order_;
  std::vector<std::vector<T>> bands_;
  std::vector<T> columns_;  // band by band, each D_l column-major
  int rest_packs_ = 0;
  std::vector<int> rest_pack_begin_;  // pack p's terms: [begin[p], begin[p + 1])
  std::vector<P> rest_columns_;       // a term's column rows in its pack
  std::vector<int> rest_inputs_;      // a term's input, among the N^2 - 1 values of bands 1..
};

// The band matrices of the rotation rotate(in, out) performs at this order (in, out: N^2 values),
// by rotating each basis vector once.
template <class T, class Rotate>
DenseRotation<T> dense_rotation(int order, Rotate&& rotate) {
  const int n = order * order;
  std::vector<std::vector<T>> bands(order);
  for (int l = 0; l < order; ++l) bands[l].assign(band_size(l) * band_size(l), T(0));
  std::vector<T> unit(n, T(0)), column(n);
  for (int j = 0; j < n; ++j) {
    unit[j] = 1;
    rotate(unit.data(), column.data());
    unit[j] = 0;
    const int l = band_of(j), size = band_size(l), col = j - l * l;
    for (int i = 0; i < size; ++i) bands[l][i * size + col] = column[l * l + i];
  }
  return DenseRotation<T>(order, std::move(bands));
}

}  // namespace zhf::runtime
