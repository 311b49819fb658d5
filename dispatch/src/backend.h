// The one interface every instruction-set path of the library implements (isa_unit.h), and the
// factories each path's units define. Standard library only: the units include it before they
// compile the runtime under their own namespace.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "zhf/dispatch/isa.h"

namespace zhf::dispatch::detail {

using dispatch::Isa;

template <class T>
class PreparedBackend {
 public:
  virtual ~PreparedBackend() = default;
  virtual void apply(std::size_t count, const T* in, T* out, int threads) const = 0;
};

template <class T>
class Backend {
 public:
  virtual ~Backend() = default;
  virtual int order() const = 0;
  virtual std::string path() const = 0;
  virtual void rotate(const T* r, const T* in, T* out) const = 0;
  virtual void rotate_rgb(const T* r, const T* in, T* out) const = 0;
  virtual void rotate_batch(std::size_t count, const T* r, const T* in, T* out, int threads) const = 0;
  virtual void transform_each(std::size_t count, const T* q, const T* in, T* out, int threads) const = 0;
  virtual std::unique_ptr<PreparedBackend<T>> prepare(const T* q, std::size_t count) const = 0;
  virtual std::vector<std::vector<T>> band_matrices(const T* q) const = 0;
  virtual void apply_splats(const T* q, std::size_t count, const T* in, T* out, int threads) const = 0;
  virtual void apply_planar(const T* q, std::size_t count, int channels, const T* in, T* out, int threads) const = 0;
};

// The fastest backend of an order 1..kMaxZxzxzOrder on path I (isa_backend.cc, one unit per path).
template <Isa I, class T>
std::unique_ptr<Backend<T>> make_backend(int order);
// runtime::all_finite compiled for path I (isa_backend.cc).
template <Isa I, class T>
bool all_finite_on(const T* p, std::size_t count);
// The generated kernels' fastest path of order N on path I (isa_order.cc, one unit per path and
// order, so the large orders compile in parallel).
template <Isa I, int N, class T>
std::unique_ptr<Backend<T>> make_generated();

}  // namespace zhf::dispatch::detail

// The units rename the token zhf before they include the runtime (isa_unit.h); they reach this
// interface through this name.
namespace zhf_dispatch_api = zhf::dispatch::detail;
