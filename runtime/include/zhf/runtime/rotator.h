// zhf's rotation library: rotate real SH vectors (zhf's convention, docs/conventions.md) by 3x3
// rotation matrices R (row-major, v -> R v; the result is the coefficients of f(R^T w)).
//
// Which call is the fast choice:
//   rotate       one vector, a new rotation each call.
//   rotate_rgb   three channels under one rotation: the per-rotation work is done once.
//   rotate_batch many vectors, each with its own rotation; spread over threads when large.
//   rotate_shared many vectors under one rotation: the band matrices are built once (dense),
//                then each vector is a small dense product; spread over threads when large.
//   dense        those band matrices, to apply yourself (~the cost of N^2 rotations to build).
//
// Where the kernels come from:
//   Rotator<T>::of<N>()                   the generated kernels of order N (include zhf_orderN.h);
//   Rotator<T>::with(gen::fastest_kernels<T>(order))
//                                         any generated order at run time, on the fastest verified
//                                         path for the instruction set compiled for (zhf_kernels.h);
//   Rotator<T>::from_table(table)         any order up to 32 from a lobe table, at a few times the
//                                         cost; its lobe stage runs in double.
#pragma once

#include <algorithm>
#include <array>
#include <cassert>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "zhf/runtime/lobe_table.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/sh_eval.h"

namespace zhf::gen {
// The functions of one generated order, specialised at the end of each zhf_orderN.h.
template <int N>
struct Kernels;
}  // namespace zhf::gen

namespace zhf::runtime {

// Below this many vectors a batch runs on the calling thread.
inline constexpr std::size_t kParallelBatchThreshold = 4096;

// Runs work(begin, end) over [0, count) in contiguous chunks, one per worker (threads = 0: all
// cores); below kParallelBatchThreshold items, or when no thread can be started, on the calling
// thread alone.
template <class Work>
void parallel_chunks(std::size_t count, int threads, Work&& work) {
  int workers = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (count < kParallelBatchThreshold) workers = 1;
  std::vector<std::thread> pool;
  const std::size_t chunk = (count + workers - 1) / workers;
  std::size_t started = chunk;  // [0, chunk) is the calling thread's
  try {
    for (int t = 1; t < workers && started < count; ++t) {
      pool.emplace_back(work, started, std::min(count, started + chunk));
      started = std::min(count, started + chunk);
    }
  } catch (const std::system_error&) {
    // No more threads (a process limit): the calling thread does the rest.
  }
  work(std::size_t(0), std::min(count, chunk));
  work(started, count);
  for (std::thread& t : pool) t.join();
}

// Whether count vectors under one rotation are cheaper through the band matrices, which cost
// about N^2 single rotations to build, than one by one.
inline bool band_matrices_pay(std::size_t count, int order) { return count >= std::size_t(order) * order; }

// One implementation of an order's single-rotation entry points.
template <class T>
struct KernelSet {
  using Kernel = void (*)(const T*, const T*, T*);
  int order = 0;
  const char* path = "";         // which implementation: "scalar" (generated kernels) or "lanes" (lanes.h)
  Kernel rotate = nullptr;       // (R, in[N^2], out[N^2])
  Kernel rotate_rgb = nullptr;   // (R, in[3][N^2], out[3][N^2]) as flat planar arrays
};

// The generated scalar kernels of order N (its header must be included).
template <int N, class T>
KernelSet<T> scalar_kernels() {
  KernelSet<T> k;
  k.order = N;
  k.path = "scalar";
  k.rotate = [](const T* r, const T* in, T* out) { gen::Kernels<N>::template rotate<T>(r, in, out); };
  // The generated RGB kernels take planar [3][N^2] arrays; the runtime API passes flat ones.
  k.rotate_rgb = [](const T* r, const T* in, T* out) {
    using Planar = T[N * N];
    gen::Kernels<N>::template rotate_rgb<T>(r, reinterpret_cast<const Planar*>(in), reinterpret_cast<Planar*>(out));
  };
  return k;
}

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
  }
  int order() const { return order_; }
  // bands()[l] is (2l+1)^2 row-major: out_l = D_l in_l.
  const std::vector<std::vector<T>>& bands() const { return bands_; }
  // out = D in for one vector of N^2 (in and out must not overlap). Cost: sum (2l+1)^2
  // multiply-adds, with fixed band sizes for the generated orders.
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
    const T* d = columns_.data();
    for (int l = 0; l < order_; ++l) {
      const int n = band_size(l), base = l * l;
      for (int i = 0; i < n; ++i) out[base + i] = 0;
      for (int j = 0; j < n; ++j, d += n)
        for (int i = 0; i < n; ++i) out[base + i] += d[i] * in[base + j];
    }
  }

 private:
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
};

template <class T>
class Rotator {
 public:
  using W = std::common_type_t<T, double>;  // the table path's lobe stage

  // The generated kernels of order N.
  template <int N>
  static Rotator of() {
    return with(scalar_kernels<N, T>());
  }

  // Any kernel set (gen::fastest_kernels, gen::scalar_kernels_of, ...).
  static Rotator with(const KernelSet<T>& kernels) {
    if (kernels.order < 1 || !kernels.rotate || !kernels.rotate_rgb)
      throw std::invalid_argument("Rotator::with: an incomplete kernel set");
    Rotator r;
    r.order_ = kernels.order;
    r.kernels_ = kernels;
    return r;
  }

  // Any order 2..32 from a lobe table. Its shape is checked here (a table built or changed by
  // hand must be safe to use); read_lobe_table has checked a file's numbers too. Throws
  // InputError naming what is wrong.
  static Rotator from_table(const LobeTable& table) {
    validate_lobe_table(table, "Rotator::from_table", TableCheck::kShape);
    Rotator r;
    r.order_ = table.order;
    r.table_ = table;
    r.legendre_ = TabulatedLegendreCoefficients(table.order);
    for (const TableBand& band : table.bands) {
      // A's structural zeros cost nothing here either (and pruned tables run faster).
      const int size = band_size(band.l);
      r.nonzeros_.emplace_back();
      for (int m = 0; m < size; ++m)
        for (int d = 0; d < size; ++d)
          if (band.inverse(m, d) != 0) r.nonzeros_.back().push_back({m, d, T(band.inverse(m, d))});
    }
    return r;
  }

  int order() const { return order_; }
  int coefficients() const { return order_ * order_; }
  // "scalar", "lanes" or "table": which implementation rotate() runs.
  std::string path() const { return kernels_.rotate ? kernels_.path : "table"; }

  // R must be a proper rotation (checked with assert in debug builds; see validate()).
  void rotate(const T r[9], const T* in, T* out) const {
    debug_check(r);
    if (kernels_.rotate) {
      kernels_.rotate(r, in, out);
    } else {
      rotate_from_table(r, in, out, 1);
    }
  }

  // Planar channels: in[c * N^2 + i], c = 0, 1, 2.
  void rotate_rgb(const T r[9], const T* in, T* out) const {
    debug_check(r);
    if (kernels_.rotate_rgb) {
      kernels_.rotate_rgb(r, in, out);
    } else {
      rotate_from_table(r, in, out, 3);
    }
  }

  // count vectors: R[9 v + k], in[N^2 v + i], out[N^2 v + i]; threads = 0: all cores.
  void rotate_batch(std::size_t count, const T* r, const T* in, T* out, int threads = 0) const {
    const std::size_t n = static_cast<std::size_t>(coefficients());
    parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) rotate(r + 9 * v, in + n * v, out + n * v);
    });
  }

  // count vectors under one rotation R: in[N^2 v + i], out[N^2 v + i]; threads = 0: all cores.
  // Through the band matrices when they pay (band_matrices_pay), else one by one.
  void rotate_shared(std::size_t count, const T r[9], const T* in, T* out, int threads = 0) const {
    const std::size_t n = static_cast<std::size_t>(coefficients());
    if (!band_matrices_pay(count, order_)) {
      for (std::size_t v = 0; v < count; ++v) rotate(r, in + n * v, out + n * v);
      return;
    }
    const DenseRotation<T> d = dense(r);
    parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) d.apply(in + n * v, out + n * v);
    });
  }

  // The band matrices of R, by rotating each basis vector once.
  DenseRotation<T> dense(const T r[9]) const {
    const int n = coefficients();
    std::vector<std::vector<T>> bands(order_);
    for (int l = 0; l < order_; ++l) bands[l].assign(band_size(l) * band_size(l), T(0));
    std::vector<T> unit(n, T(0)), column(n);
    for (int j = 0; j < n; ++j) {
      unit[j] = 1;
      rotate(r, unit.data(), column.data());
      unit[j] = 0;
      const int l = band_of(j), size = band_size(l), col = j - l * l;
      for (int i = 0; i < size; ++i) bands[l][i * size + col] = column[l * l + i];
    }
    return DenseRotation<T>(order_, std::move(bands));
  }

  static RotationCheck validate(const T r[9], double max_defect = tolerance::kRotationDefect) {
    return validate_rotation(r, max_defect);
  }

 private:
  Rotator() = default;

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
    for (std::size_t d = 0; d < table_.lobes.size(); ++d)
      for (int i = 0; i < 3; ++i)
        rotated[d][i] = q[3 * i] * table_.lobes[d].xyz[0] + q[3 * i + 1] * table_.lobes[d].xyz[1] +
                        q[3 * i + 2] * table_.lobes[d].xyz[2];
    std::vector<std::vector<W>> y_rotated(table_.bands.size());
    for (std::size_t b = 0; b < table_.bands.size(); ++b) {
      const int size = band_size(table_.bands[b].l);
      y_rotated[b].resize(size * size);  // [d * size + m]
      for (int d = 0; d < size; ++d)
        eval_band<W>(table_.bands[b].l, rotated[table_.bands[b].lobes[d]].data(), &y_rotated[b][d * size], legendre_);
    }
    std::vector<T> z;
    for (int c = 0; c < channels; ++c) {
      const T* f = in + c * n;
      T* g = out + c * n;
      g[0] = f[0];
      if (order_ > 1) rotate_band1(r, f + 1, g + 1);
      for (std::size_t b = 0; b < table_.bands.size(); ++b) {
        const TableBand& band = table_.bands[b];
        const int size = band_size(band.l), base = band.l * band.l;
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
  KernelSet<T> kernels_;
  struct Nonzero {
    int m, d;
    T value;  // A_l[m][d]
  };
  LobeTable table_;
  TabulatedLegendreCoefficients legendre_{0};
  std::vector<std::vector<Nonzero>> nonzeros_;  // per band, row-major order
};

}  // namespace zhf::runtime
