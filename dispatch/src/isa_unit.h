// Included first by every unit of one instruction-set path (isa_order.cc, isa_backend.cc), each
// compiled with that path's flags (dispatch/CMakeLists.txt) and with ZHF_DISPATCH_ISA (an Isa
// enumerator) and ZHF_DISPATCH_NAMESPACE defined.
//
// The runtime is header-only: its inline functions and templates compiled here under another
// instruction set keep their mangled names, and the linker would merge them with another path's
// copy (or the baseline one the rest of zhf uses). So the token zhf is renamed to the path's own
// namespace before the runtime is included; the interface is reached as zhf_dispatch_api.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "backend.h"

#if !defined(ZHF_DISPATCH_ISA) || !defined(ZHF_DISPATCH_NAMESPACE)
#error "a dispatch unit needs ZHF_DISPATCH_ISA and ZHF_DISPATCH_NAMESPACE"
#endif

#define zhf ZHF_DISPATCH_NAMESPACE
#include "zhf/runtime/dense_rotation.h"
#include "zhf/runtime/finite.h"
#include "zhf/runtime/orthogonal.h"
#include "zhf/runtime/parallel.h"
#include "zhf/runtime/rotator.h"
#include "zhf/runtime/soa_batch.h"
#include "zhf_paths.h"

namespace zhf::dispatch_unit {

namespace api = zhf_dispatch_api;
inline constexpr api::Isa kIsa = api::Isa::ZHF_DISPATCH_ISA;

// An orthogonal transform prepared for count vectors (runtime::OrthogonalTransform::prepare).
template <class T>
class IsaPrepared final : public api::PreparedBackend<T> {
 public:
  IsaPrepared(const runtime::Rotator<T>& rotator, const T* q, std::size_t count);
  IsaPrepared(const IsaPrepared&) = delete;  // prepared_ refers to transform_
  IsaPrepared& operator=(const IsaPrepared&) = delete;
  void apply(std::size_t count, const T* in, T* out, int threads) const override;

 private:
  runtime::OrthogonalTransform<T> transform_;
  typename runtime::OrthogonalTransform<T>::Prepared prepared_;
  std::size_t n_;
};

// A runtime::Rotator of this path behind the library's interface. Its members are compiled once
// per path, in isa_backend.cc (the extern declarations below): the per-order units only make one, so
// the dense band products of every order are not compiled again in each of them.
template <class T>
class IsaBackend final : public api::Backend<T> {
 public:
  explicit IsaBackend(runtime::Rotator<T> rotator);
  int order() const override;
  std::string path() const override;
  void rotate(const T* r, const T* in, T* out) const override;
  void rotate_rgb(const T* r, const T* in, T* out) const override;
  void rotate_batch(std::size_t count, const T* r, const T* in, T* out, int threads) const override;
  void transform_each(std::size_t count, const T* q, const T* in, T* out, int threads) const override;
  std::unique_ptr<api::PreparedBackend<T>> prepare(const T* q, std::size_t count) const override;
  std::vector<std::vector<T>> band_matrices(const T* q) const override;
  void apply_splats(const T* q, std::size_t count, const T* in, T* out, int threads) const override;
  void apply_planar(const T* q, std::size_t count, int channels, const T* in, T* out, int threads) const override;

 private:
  runtime::Rotator<T> rotator_;
};

extern template class IsaBackend<float>;
extern template class IsaBackend<double>;

// Whether per-item rotations of order N in T (rotate_batch, transform_each) run through SoA
// blocks (runtime::rotate_items) rather than the kernel set's own batch: where they measured
// faster (benchmarks/results/per_item_<path>.txt), in float at orders 3..8 on the x86-64 paths,
// in double at 3..8 with AVX-512 and 4..8 with AVX2 (at order 3 the transposes outweigh the 4
// double lanes). Order 2 keeps its own (bands 0 and 1 in one register). Paths not measured keep
// their own.
template <int N, class T>
constexpr bool items_in_lanes() {
  if constexpr (gen::Kernels<N>::kLobeStage != 0 || N < 3) return false;
  if constexpr (std::is_same_v<T, float>) return kIsa == api::Isa::kSse2 || kIsa == api::Isa::kAvx2 || kIsa == api::Isa::kAvx512;
  return kIsa == api::Isa::kAvx512 || (kIsa == api::Isa::kAvx2 && N >= 4);
}

// The fastest kernels of generated order N (zhf_paths.h's choice for this instruction set; the
// unit includes zhf_orderN.h), with the per-item batch items_in_lanes picks.
template <int N, class T>
std::unique_ptr<api::Backend<T>> generated() {
  runtime::KernelSet<T> kernels = gen::fastest_kernels<N, T>();
  if constexpr (items_in_lanes<N, T>()) kernels.rotate_batch = &runtime::rotate_items<N, T>;
  return std::make_unique<IsaBackend<T>>(runtime::Rotator<T>::with(kernels));
}

}  // namespace zhf::dispatch_unit
