// zhf::dispatch::Rotator<T>: the rotation library compiled for several instruction sets, on the
// fastest path the CPU runs (isa.h). Conventions as the header-only runtime::Rotator
// (runtime/rotator.h): real SH without the Condon-Shortley phase, R row-major mapping v to R v,
// the result holding the coefficients of f(R^T w); float or double.
//
// make(order) takes, for the path picked, the fastest verified kernels of the order: the
// generated ones at orders 2..8 (zhf_kernels.h's fastest_kernels), zxzxz at orders 1 and 9..128
// (runtime::Rotator::zxzxz); make(order, &table) a lobe table's rotation
// (runtime::Rotator::from_table) on that path. Every caller in zhf (the CLI, the Python module,
// splat) comes in through make, so which kernels run is decided here alone. Accuracy and cost are the chosen kernels'
// (docs/performance.md); each call below costs one indirect call on top, which the batch calls
// pay once per call, not per vector.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "zhf/dispatch/isa.h"
#include "zhf/runtime/lobe_table.h"

namespace zhf::dispatch {

namespace detail {
template <class T>
class Backend;
template <class T>
class PreparedBackend;
}  // namespace detail

// One orthogonal transform prepared for many vectors (Rotator::prepare); it keeps what it needs
// of its Rotator alive.
template <class T>
class PreparedTransform {
 public:
  // count vectors in[N^2 v + i] to out; threads = 0: all cores.
  void apply(std::size_t count, const T* in, T* out, int threads = 0) const;

 private:
  template <class>
  friend class Rotator;
  std::shared_ptr<const detail::Backend<T>> backend_;  // the prepared transform refers to it
  std::shared_ptr<const detail::PreparedBackend<T>> prepared_;
};

template <class T>
class Rotator {
 public:
  // The fastest rotator of an order 1..128 on active_isa(); with a table (not null), that table's
  // rotation instead, of its order (2..32). Throws std::invalid_argument for any other order,
  // runtime::InputError for a table of another order or shape (validate_lobe_table's kShape), or
  // std::invalid_argument when ZHF_ISA is wrong (isa.h).
  static Rotator make(int order, const runtime::LobeTable* table = nullptr);

  int order() const;
  int coefficients() const { return order() * order(); }
  Isa isa() const { return isa_; }
  // Which kernels run: "scalar", "lanes", "band_rows", "bands01" or "zxzxz" (order 1 among its orders).
  std::string path() const;

  // R must be a proper rotation; in and out must not overlap (as every call below).
  void rotate(const T r[9], const T* in, T* out) const;
  // Three channels under one R, planar: in[c N^2 + i].
  void rotate_rgb(const T r[9], const T* in, T* out) const;
  // count vectors, each its own rotation: r[9 v + k], in[N^2 v + i]; threads = 0: all cores.
  void rotate_batch(std::size_t count, const T* r, const T* in, T* out, int threads = 0) const;

  // Orthogonal transforms (rotations and reflections, det -1: runtime/orthogonal.h).
  // count vectors, each under its own q[9 v + k]:
  void transform_each(std::size_t count, const T* q, const T* in, T* out, int threads = 0) const;
  // count vectors under one q, through the band matrices where they pay:
  void transform_shared(std::size_t count, const T q[9], const T* in, T* out, int threads = 0) const;
  // q prepared once for about count vectors, to apply in parts (the same work transform_shared
  // does before its vectors):
  PreparedTransform<T> prepare(const T q[9], std::size_t count) const;
  // The band matrices of q: bands[l] is (2l+1)^2 row-major, out_l = D_l in_l.
  std::vector<std::vector<T>> band_matrices(const T q[9]) const;
  // One q over count 3DGS splats (3 N^2 values each: three band-0 values, then bands 1.. of each
  // channel) or over planes (channels N^2 planes of count values); in == out is allowed. As
  // runtime::DenseRotation's apply_splats and apply_planar.
  void apply_splats(const T q[9], std::size_t count, const T* in, T* out, int threads = 0) const;
  void apply_planar(const T q[9], std::size_t count, int channels, const T* in, T* out, int threads = 0) const;

 private:
  Rotator() = default;
  std::shared_ptr<const detail::Backend<T>> backend_;
  Isa isa_ = Isa::kGeneric;
};

extern template class PreparedTransform<float>;
extern template class PreparedTransform<double>;
extern template class Rotator<float>;
extern template class Rotator<double>;

}  // namespace zhf::dispatch
