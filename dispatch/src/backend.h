// The one interface every instruction-set path of the library implements (isa_unit.h), and the
// factories each path's units define. Standard library only: the units include it before they
// compile the runtime under their own namespace.
#pragma once

#include <array>
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

// A lobe table in standard types, to cross from the library into a path's units, where the
// runtime's LobeTable is another type (isa_unit.h renames its namespace). Its fields have
// LobeTable's names, so one template copies either way (copy_table).
struct TableData {
  struct Lobe {
    double theta = 0, phi = 0;
    std::array<double, 3> xyz{};
  };
  struct Inverse {
    int rows = 0, cols = 0;
    std::vector<double> values;
  };
  struct Band {
    int l = 0, zeros = 0;
    double condition = 0;
    std::vector<int> lobes;
    Inverse inverse;
  };
  int order = 0, zeros = 0, entries = 0;
  bool lobe_sharing = true;
  std::vector<Lobe> lobes;
  std::vector<Band> bands;
};

// The fields a rotation reads, from one table type into another (LobeTable <-> TableData).
template <class To, class From>
To copy_table(const From& from) {
  To to;
  to.order = from.order, to.zeros = from.zeros, to.entries = from.entries, to.lobe_sharing = from.lobe_sharing;
  to.lobes.resize(from.lobes.size());
  for (std::size_t i = 0; i < from.lobes.size(); ++i)
    to.lobes[i].theta = from.lobes[i].theta, to.lobes[i].phi = from.lobes[i].phi, to.lobes[i].xyz = from.lobes[i].xyz;
  to.bands.resize(from.bands.size());
  for (std::size_t i = 0; i < from.bands.size(); ++i) {
    const auto& f = from.bands[i];
    auto& t = to.bands[i];
    t.l = f.l, t.zeros = f.zeros, t.condition = f.condition, t.lobes = f.lobes;
    t.inverse.rows = f.inverse.rows, t.inverse.cols = f.inverse.cols, t.inverse.values = f.inverse.values;
  }
  return to;
}

// The fastest backend of an order 1..kMaxZxzxzOrder on path I (isa_backend.cc, one unit per path).
template <Isa I, class T>
std::unique_ptr<Backend<T>> make_backend(int order);
// runtime::Rotator::from_table of a table already checked (validate_lobe_table's kShape), on path I
// (isa_backend.cc).
template <Isa I, class T>
std::unique_ptr<Backend<T>> make_table_backend(const TableData& table);
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
