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
//                                         any generated order (kMinGeneratedOrder..kMaxGeneratedOrder)
//                                         at run time, on the fastest verified path for the
//                                         instruction set compiled for (zhf_kernels.h);
//   Rotator<T>::from_table(table)         any order up to 32 from a lobe table: below
//                                         kZxzxzFromOrder the lobes (table_rotation.h), from it zxzxz
//                                         (zxzxz_rotation.h), the faster by measurement;
//   Rotator<T>::zxzxz(order)              any order up to 128, no table (zxzxz_rotation.h).
// Accuracy: double within tolerance::kDouble (zxzxz above kMaxDoubleAccurateZxzxzOrder:
// kHighOrderZxzxzDouble); float generated kernels within kFloatRotation on
// random unit inputs, the run-time orders (from_table, zxzxz) within kRuntimeOrdersFloat.
// Both run float orders kBandRowsMinOrder..kBandRowsMaxOrder through the band rows (band_rows.h:
// zxzxz across AVX2 lanes), and order 2 through its bands 0 and 1 in one register, in builds that
// have them.
#pragma once

#include <cassert>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "zhf/runtime/band_rows.h"
#include "zhf/runtime/dense_rotation.h"
#include "zhf/runtime/kernel_set.h"
#include "zhf/runtime/lobe_table.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/runtime/table_rotation.h"
#include "zhf/runtime/tolerances.h"
#include "zhf/runtime/zxzxz_rotation.h"

namespace zhf::gen {
// The functions of one generated order, specialised at the end of each zhf_orderN.h.
template <int N>
struct Kernels;
}  // namespace zhf::gen

namespace zhf::runtime {

// From this order on, Rotator::from_table runs zxzxz, by measurement (benchmarks/runtime_paths_bench.cc,
// benchmarks/NOTES.md): built for AVX2 the lobe path is 1.06x ahead at order 3 and zxzxz from 4
// (1.2x at 4, 2.3x at 7, 4.9x at 12, 13x at 32); elsewhere (a 4-double pack is two or more
// instructions) zxzxz is ahead at every order (2.4x at 3, 3.1x at 8).
#if defined(__AVX2__)
inline constexpr int kZxzxzFromOrder = 4;
#else
inline constexpr int kZxzxzFromOrder = kMinTableOrder;
#endif

// Whether count vectors under one rotation are cheaper through the band matrices, which cost
// about N^2 single rotations to build, than one by one.
inline bool band_matrices_pay(std::size_t count, int order) { return count >= std::size_t(order) * order; }

// The generated scalar kernels of order N (its header must be included).
template <int N, class T>
KernelSet<T> scalar_kernels() {
  KernelSet<T> k;
  k.order = N;
  k.path = "scalar";
  k.rotate = &gen::Kernels<N>::template rotate<T>;
  k.rotate_batch = &rotate_each<T, N, &gen::Kernels<N>::template rotate<T>>;
  // The generated RGB kernels take planar [3][N^2] arrays; the runtime API passes flat ones.
  k.rotate_rgb = [](const T* r, const T* in, T* out) {
    using Planar = T[N * N];
    gen::Kernels<N>::template rotate_rgb<T>(r, reinterpret_cast<const Planar*>(in), reinterpret_cast<Planar*>(out));
  };
  return k;
}

template <class T>
class Rotator {
 public:
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
    if constexpr (kHasBandRows) {
      if (band_rows_hold(table.order)) return with(band_rows_kernels(table.order));
    }
    Rotator r;
    r.order_ = table.order;
    if (table.order >= kZxzxzFromOrder) {
      r.zxzxz_ = ZxzxzRotation<T>(table.order);
    } else {
      r.table_ = TableRotation<T>(table);
    }
    return r;
  }

  // Any order 1..kMaxZxzxzOrder through zxzxz, no table needed; throws std::invalid_argument for
  // any other order.
  static Rotator zxzxz(int order) {
    if constexpr (kHasBandRows) {
      if (band_rows_hold(order)) return with(band_rows_kernels(order));
    }
    Rotator r;
    r.zxzxz_ = ZxzxzRotation<T>(order);
    r.order_ = order;
    return r;
  }

  int order() const { return order_; }
  int coefficients() const { return order_ * order_; }
  // "scalar", "lanes", "band_rows", "bands01", "table" or "zxzxz": which implementation rotate() runs.
  std::string path() const { return kernels_.rotate ? kernels_.path : zxzxz_.order() ? "zxzxz" : "table"; }

  // R must be a proper rotation (checked with assert in debug builds; see validate()).
  void rotate(const T r[9], const T* in, T* out) const {
    debug_check(r);
    if (kernels_.rotate) {
      kernels_.rotate(r, in, out);
    } else {
      run_table(r, in, out, 1);
    }
  }

  // Planar channels: in[c * N^2 + i], c = 0, 1, 2.
  void rotate_rgb(const T r[9], const T* in, T* out) const {
    debug_check(r);
    if (kernels_.rotate_rgb) {
      kernels_.rotate_rgb(r, in, out);
    } else {
      run_table(r, in, out, 3);
    }
  }

  // count vectors: R[9 v + k], in[N^2 v + i], out[N^2 v + i]; threads = 0: all cores.
  void rotate_batch(std::size_t count, const T* r, const T* in, T* out, int threads = 0) const {
    const std::size_t n = static_cast<std::size_t>(coefficients());
    parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
      if (kernels_.rotate_batch) return kernels_.rotate_batch(end - begin, r + 9 * begin, in + n * begin, out + n * begin);
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
    return dense_rotation<T>(order_, [&](const T* in, T* out) { rotate(r, in, out); });
  }

  static RotationCheck validate(const T r[9], double max_defect = tolerance::kRotationDefect) {
    return validate_rotation(r, max_defect);
  }

 private:
  Rotator() = default;

  // Float orders band_rows_hold run through band_rows.h where it is built.
  static constexpr bool kHasBandRows = std::is_same_v<T, float> && kBandRowsBuilt;

  void run_table(const T r[9], const T* in, T* out, int channels) const {
    if (zxzxz_.order()) {
      zxzxz_.rotate(r, in, out, channels);
    } else {
      table_.rotate(r, in, out, channels);
    }
  }

  void debug_check(const T r[9]) const {
    (void)r;
    assert(validate_rotation(r).ok && "zhf: not a proper rotation; see Rotator::validate");
  }

  int order_ = 0;
  KernelSet<T> kernels_;
  TableRotation<T> table_;
  ZxzxzRotation<T> zxzxz_;
};

}  // namespace zhf::runtime
