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
// runtime's LobeTable is another type (isa_unit.h renames its namespace). Both sides convert with
// the templates below, field by field, from and into their own LobeTable.
struct TableData {
  struct Lobe {
    double theta, phi;
    std::array<double, 3> xyz;
  };
  struct Band {
    int l, rows, cols, zeros;
    double condition;
    std::vector<int> lobes;
    std::vector<double> inverse;
  };
  int order = 0, zeros = 0, entries = 0;
  bool lobe_sharing = true;
  std::vector<Lobe> lobes;
  std::vector<Band> bands;
};

template <class Table>
TableData table_data(const Table& t) {
  TableData d;
  d.order = t.order, d.zeros = t.zeros, d.entries = t.entries, d.lobe_sharing = t.lobe_sharing;
  for (const auto& lobe : t.lobes) d.lobes.push_back({lobe.theta, lobe.phi, lobe.xyz});
  for (const auto& b : t.bands) d.bands.push_back({b.l, b.inverse.rows, b.inverse.cols, b.zeros, b.condition, b.lobes, b.inverse.values});
  return d;
}

template <class Table>
Table table_of(const TableData& d) {
  Table t;
  t.order = d.order, t.zeros = d.zeros, t.entries = d.entries, t.lobe_sharing = d.lobe_sharing;
  for (const TableData::Lobe& lobe : d.lobes) {
    t.lobes.emplace_back();
    t.lobes.back().theta = lobe.theta, t.lobes.back().phi = lobe.phi, t.lobes.back().xyz = lobe.xyz;
  }
  for (const TableData::Band& b : d.bands) {
    t.bands.emplace_back();
    auto& band = t.bands.back();
    band.l = b.l, band.zeros = b.zeros, band.condition = b.condition, band.lobes = b.lobes;
    band.inverse.rows = b.rows, band.inverse.cols = b.cols, band.inverse.values = b.inverse;
  }
  return t;
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
