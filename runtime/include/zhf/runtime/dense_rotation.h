// DenseRotation: the band matrices of one rotation, built once (Rotator::dense, about the cost of
// N^2 single rotations) and applied to many vectors: one at a time, 3D Gaussian Splatting's
// interleaved RGB layout, or planar arrays. Convention as Rotator: out_l = D_l in_l.
#pragma once

#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

#include "zhf/runtime/limits.h"
#include "zhf/runtime/pack.h"
#include "zhf/runtime/parallel.h"
#include "zhf/runtime/sh_eval.h"

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
      rest_pack_begin_.push_back(static_cast<int>(rest_terms_.size()));
      for (int l = 1; l < order_; ++l) {
        const int n = band_size(l), first_row = l * l - 1;
        if (first_row >= (p + 1) * P::kLanes || first_row + n <= p * P::kLanes) continue;
        for (int j = 0; j < n; ++j) {
          T lanes[P::kLanes] = {};
          for (int k = 0; k < P::kLanes; ++k) {
            const int row = p * P::kLanes + k - first_row;
            if (row >= 0 && row < n) lanes[k] = bands_[l][row * n + j];
          }
          rest_terms_.push_back({first_row + j, P::load(lanes)});
        }
      }
    }
    rest_pack_begin_.push_back(static_cast<int>(rest_terms_.size()));
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
  // scalar multiply-adds); docs/performance.md compares it with memory bandwidth.
  void apply_splats(std::size_t count, const T* in, T* out, int threads = 0) const {
    const std::size_t rest = static_cast<std::size_t>(coefficients() - 1), item = 3 + 3 * rest;
    parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) {
        const T* f = in + item * v;
        T* g = out + item * v;
        for (int c = 0; c < 3; ++c) g[c] = f[c];
        for (int c = 0; c < 3; ++c) apply_rest(f + 3 + c * rest, g + 3 + c * rest);
      }
    });
  }

  // Planar layout: plane p = c N^2 + i holds coefficient i of channel c of every item,
  // in[p count + v], for channels planes sets. in == out is allowed. Runs Pack<T>::kLanes items
  // per step; the same multiply-adds as apply() per item.
  void apply_planar(std::size_t count, int channels, const T* in, T* out, int threads = 0) const {
    const std::size_t planes = static_cast<std::size_t>(coefficients()) * count;  // one channel's
    parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
      const std::size_t whole = begin + (end - begin) / P::kLanes * P::kLanes;
      for (int c = 0; c < channels; ++c) {
        const T* f = in + planes * static_cast<std::size_t>(c);
        T* g = out + planes * static_cast<std::size_t>(c);
        for (std::size_t v = begin; v < whole; v += P::kLanes) apply_planar_step<P>(f + v, g + v, count);
        for (std::size_t v = whole; v < end; ++v) apply_planar_step<T>(f + v, g + v, count);
      }
    });
  }

 private:
  using P = Pack<T>;
  struct RestTerm {
    int input;  // position among the N^2 - 1 values of bands 1..
    P column;   // its column's rows in this pack
  };

  // y = D x over bands 1.. (N^2 - 1 values each); x may be y (every pack is formed before any
  // is stored).
  void apply_rest(const T* x, T* y) const {
    P acc[(kMaxZxzxzOrder * kMaxZxzxzOrder + P::kLanes - 1) / P::kLanes];  // any Rotator's order
    for (int p = 0; p < rest_packs_; ++p) {
      // Four partial sums: one would be a chain of dependent multiply-adds.
      P sum[4] = {P(0.0), P(0.0), P(0.0), P(0.0)};
      const RestTerm* term = &rest_terms_[rest_pack_begin_[p]];
      const int terms = rest_pack_begin_[p + 1] - rest_pack_begin_[p];
      int t = 0;
      for (; t + 4 <= terms; t += 4)
        for (int k = 0; k < 4; ++k) sum[k] += term[t + k].column * P::broadcast(x[term[t + k].input]);
      for (; t < terms; ++t) sum[t % 4] += term[t].column * P::broadcast(x[term[t].input]);
      acc[p] = (sum[0] + sum[1]) + (sum[2] + sum[3]);
    }
    const int rest = coefficients() - 1, whole = rest / P::kLanes;
    for (int p = 0; p < whole; ++p) acc[p].store(y + p * P::kLanes);
    if (whole < rest_packs_) {
      T lanes[P::kLanes];
      acc[whole].store(lanes);
      // A few scalar stores: a memcpy of run-time length is a library call.
      for (int k = 0; k < rest - whole * P::kLanes; ++k) y[whole * P::kLanes + k] = lanes[k];
    }
  }

  // One step of apply_planar over V (a Pack: kLanes items; T: one item); planes count apart.
  template <class V>
  void apply_planar_step(const T* in, T* out, std::size_t count) const {
    auto constant = [](T c) {
      if constexpr (std::is_same_v<V, T>) return c;
      else return V::broadcast(c);
    };
    auto load = [&](int i) {
      if constexpr (std::is_same_v<V, T>) return in[i * count];
      else return V::load(in + i * count);
    };
    auto store = [&](int i, const V& value) {
      if constexpr (std::is_same_v<V, T>) out[i * count] = value;
      else value.store(out + i * count);
    };
    store(0, load(0));
    const T* d = columns_.data() + 1;
    for (int l = 1; l < order_; ++l) {
      const int n = band_size(l), base = l * l;
      V x[2 * kMaxZxzxzOrder - 1];
      for (int j = 0; j < n; ++j) x[j] = load(base + j);
      for (int i = 0; i < n; ++i) {
        V sum = constant(0);
        for (int j = 0; j < n; ++j) sum += constant(d[j * n + i]) * x[j];
        store(base + i, sum);
      }
      d += n * n;
    }
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
  std::vector<RestTerm> rest_terms_;
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
