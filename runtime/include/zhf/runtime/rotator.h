// zhf's rotation library: rotate real SH vectors (zhf's convention, see README) by 3x3
// rotation matrices R (row-major, v -> R v; the result is the coefficients of f(R^T w)).
//
// Which call is the fast choice:
//   rotate       one vector, a new rotation each call: the generated kernels (orders 2..8).
//   rotate_rgb   three channels under one rotation: the per-rotation work is done once.
//   rotate_batch many vectors, each with its own rotation; spread over threads when large.
//   dense        one rotation shared by many vectors: build the band matrices once
//                (~the cost of N^2/3 rotations), then each apply is a small dense product.
// A rotator from a lobe table (from_table) handles any order up to 32 at a few times the cost
// of the generated kernels; use it when the order is only known at run time. Like the generated
// kernels of orders whose float error model needs it, it runs the lobe stage in double
// (see codegen/kernels.h, LobePrecision).
#pragma once

#include <algorithm>
#include <array>
#include <cassert>
#include <stdexcept>
#include <thread>
#include <type_traits>
#include <vector>

#include "zhf/runtime/lobe_table.h"
#include "zhf/runtime/polar_step.h"
#include "zhf/runtime/rotation_check.h"
#include "zhf_order2.h"
#include "zhf_order3.h"
#include "zhf_order4.h"
#include "zhf_order5.h"
#include "zhf_order6.h"
#include "zhf_order7.h"
#include "zhf_order8.h"

namespace zhf::runtime {

inline constexpr int kMinGeneratedOrder = 2;
inline constexpr int kMaxGeneratedOrder = 8;
// Below this many vectors a batch runs on the calling thread.
inline constexpr std::size_t kParallelBatchThreshold = 4096;

// Build-once, apply-many band matrices of one rotation.
template <class T>
class DenseRotation {
 public:
  DenseRotation(int order, std::vector<std::vector<T>> bands) : order_(order), bands_(std::move(bands)) {}
  int order() const { return order_; }
  // bands()[l] is (2l+1)^2 row-major: out_l = D_l in_l.
  const std::vector<std::vector<T>>& bands() const { return bands_; }
  void apply(const T* in, T* out) const {
    for (int l = 0; l < order_; ++l) {
      const int n = 2 * l + 1, base = l * l;
      const T* d = bands_[l].data();
      for (int i = 0; i < n; ++i) {
        T sum = 0;
        for (int j = 0; j < n; ++j) sum += d[i * n + j] * in[base + j];
        out[base + i] = sum;
      }
    }
  }

 private:
  int order_;
  std::vector<std::vector<T>> bands_;
};

template <class T>
class Rotator {
 public:
  using Kernel = void (*)(const T*, const T*, T*);
  using W = std::common_type_t<T, double>;  // the table path's lobe stage

  // The compiled kernels of generated/cpp for order 2..8.
  static Rotator generated(int order) {
    Rotator r;
    r.order_ = order;
    switch (order) {
      case 2: r.bind<2>(gen::rotate_order2<T>); break;
      case 3: r.bind<3>(gen::rotate_order3<T>); break;
      case 4: r.bind<4>(gen::rotate_order4<T>); break;
      case 5: r.bind<5>(gen::rotate_order5<T>); break;
      case 6: r.bind<6>(gen::rotate_order6<T>); break;
      case 7: r.bind<7>(gen::rotate_order7<T>); break;
      case 8: r.bind<8>(gen::rotate_order8<T>); break;
      default: throw std::invalid_argument("Rotator::generated: order " + std::to_string(order) + " is not in [2, 8]");
    }
    return r;
  }

  // Any order 2..32 from a parsed lobe table.
  static Rotator from_table(const LobeTableData& table) {
    Rotator r;
    r.order_ = table.order;
    r.table_ = table;
    for (const RuntimeBand& band : table.bands) {
      r.evaluators_.emplace_back(band.l);
      // A's structural zeros cost nothing here either (and pruned tables run faster).
      const int size = 2 * band.l + 1;
      r.nonzeros_.emplace_back();
      for (int m = 0; m < size; ++m)
        for (int d = 0; d < size; ++d)
          if (band.inverse[m * size + d] != 0) r.nonzeros_.back().push_back({m, d, T(band.inverse[m * size + d])});
    }
    return r;
  }

  int order() const { return order_; }
  int coefficients() const { return order_ * order_; }

  // R must be a proper rotation (checked with assert in debug builds; see validate()).
  void rotate(const T r[9], const T* in, T* out) const {
    debug_check(r);
    if (kernel_) {
      kernel_(r, in, out);
    } else {
      rotate_from_table(r, in, out, 1);
    }
  }

  // Planar channels: in[c * N^2 + i], c = 0, 1, 2.
  void rotate_rgb(const T r[9], const T* in, T* out) const {
    debug_check(r);
    if (rgb_kernel_) {
      rgb_kernel_(r, in, out);
    } else {
      rotate_from_table(r, in, out, 3);
    }
  }

  // count vectors: R[9 v + k], in[N^2 v + i], out[N^2 v + i]; threads = 0: all cores.
  void rotate_batch(std::size_t count, const T* r, const T* in, T* out, int threads = 0) const {
    const std::size_t n = static_cast<std::size_t>(coefficients());
    auto work = [&](std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) rotate(r + 9 * v, in + n * v, out + n * v);
    };
    int workers = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    if (count < kParallelBatchThreshold) workers = 1;
    std::vector<std::thread> pool;
    const std::size_t chunk = (count + workers - 1) / workers;
    for (int t = 1; t < workers; ++t) {
      const std::size_t begin = std::min(count, t * chunk), end = std::min(count, (t + 1) * chunk);
      if (begin < end) pool.emplace_back(work, begin, end);
    }
    work(0, std::min(count, chunk));
    for (std::thread& t : pool) t.join();
  }

  // The band matrices of R, by rotating each basis vector once.
  DenseRotation<T> dense(const T r[9]) const {
    const int n = coefficients();
    std::vector<std::vector<T>> bands(order_);
    for (int l = 0; l < order_; ++l) bands[l].assign((2 * l + 1) * (2 * l + 1), T(0));
    std::vector<T> unit(n, T(0)), column(n);
    for (int j = 0; j < n; ++j) {
      unit[j] = 1;
      rotate(r, unit.data(), column.data());
      unit[j] = 0;
      int l = 0;
      while ((l + 1) * (l + 1) <= j) ++l;
      const int size = 2 * l + 1, col = j - l * l;
      for (int i = 0; i < size; ++i) bands[l][i * size + col] = column[l * l + i];
    }
    return DenseRotation<T>(order_, std::move(bands));
  }

  static RotationCheck validate(const T r[9], double tolerance = kDefaultRotationTolerance) {
    return validate_rotation(r, tolerance);
  }

 private:
  template <int N>
  void bind(Kernel kernel) {
    kernel_ = kernel;
    // The generated RGB kernels take planar [3][N^2] arrays; the runtime API passes flat ones.
    rgb_kernel_ = [](const T* r, const T* in, T* out) {
      using Planar = T[N * N];
      rgb_dispatch<N>(r, reinterpret_cast<const Planar*>(in), reinterpret_cast<Planar*>(out));
    };
  }

  template <int N>
  static void rgb_dispatch(const T* r, const T (*in)[N * N], T (*out)[N * N]) {
    if constexpr (N == 2) gen::rotate_rgb_order2<T>(r, in, out);
    if constexpr (N == 3) gen::rotate_rgb_order3<T>(r, in, out);
    if constexpr (N == 4) gen::rotate_rgb_order4<T>(r, in, out);
    if constexpr (N == 5) gen::rotate_rgb_order5<T>(r, in, out);
    if constexpr (N == 6) gen::rotate_rgb_order6<T>(r, in, out);
    if constexpr (N == 7) gen::rotate_rgb_order7<T>(r, in, out);
    if constexpr (N == 8) gen::rotate_rgb_order8<T>(r, in, out);
  }

  void debug_check(const T r[9]) const {
    (void)r;
    assert(validate_rotation(r).ok && "zhf: not a proper rotation; see Rotator::validate");
  }

  // The loop form of the generated kernel: z = A^T f, SH at Q w_d, dense Y_Q^T z, with Q the
  // projection of R onto the rotations, the lobe stage in W. The SH values at the rotated
  // lobes are computed once and shared by the channels.
  void rotate_from_table(const T r[9], const T* in, T* out, int channels) const {
    const int n = coefficients();
    W q[9];
    polar_step(r, q);
    std::vector<std::array<W, 3>> rotated(table_.lobes.size());
    for (size_t d = 0; d < table_.lobes.size(); ++d)
      for (int i = 0; i < 3; ++i)
        rotated[d][i] = q[3 * i] * table_.lobes[d][0] + q[3 * i + 1] * table_.lobes[d][1] + q[3 * i + 2] * table_.lobes[d][2];
    std::vector<std::vector<W>> y_rotated(table_.bands.size());
    for (size_t b = 0; b < table_.bands.size(); ++b) {
      const int size = 2 * table_.bands[b].l + 1;
      y_rotated[b].resize(size * size);  // [d * size + m]
      for (int d = 0; d < size; ++d) evaluators_[b](rotated[table_.bands[b].lobes[d]].data(), &y_rotated[b][d * size]);
    }
    std::vector<T> z;
    for (int c = 0; c < channels; ++c) {
      const T* f = in + c * n;
      T* g = out + c * n;
      g[0] = f[0];
      if (order_ > 1) {
        // Band 1 is c (y, z, x): element m is axis {1, 2, 0}[m + 1].
        static constexpr int kAxis[3] = {1, 2, 0};
        for (int i = 0; i < 3; ++i) {
          T sum = 0;
          for (int j = 0; j < 3; ++j) sum += r[3 * kAxis[i] + kAxis[j]] * f[1 + j];
          g[1 + i] = sum;
        }
      }
      for (size_t b = 0; b < table_.bands.size(); ++b) {
        const RuntimeBand& band = table_.bands[b];
        const int size = 2 * band.l + 1, base = band.l * band.l;
        z.assign(size, T(0));
        for (const Nonzero& a : nonzeros_[b]) z[a.d] += a.value * f[base + a.m];
        for (int m = 0; m < size; ++m) {
          W sum = 0;
          for (int d = 0; d < size; ++d) sum += y_rotated[b][d * size + m] * W(z[d]);
          g[base + m] = T(sum);
        }
      }
    }
  }

  int order_ = 0;
  Kernel kernel_ = nullptr;
  void (*rgb_kernel_)(const T*, const T*, T*) = nullptr;
  struct Nonzero {
    int m, d;
    T value;  // A_l[m][d]
  };
  LobeTableData table_;
  std::vector<BandEvaluator<W>> evaluators_;
  std::vector<std::vector<Nonzero>> nonzeros_;  // per band, row-major order
};

}  // namespace zhf::runtime
