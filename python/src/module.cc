// zhf._zhf: the C++ half of the Python module. It takes arrays the Python half (zhf/__init__.py)
// has already shaped: contiguous (count, N^2) coefficients of one dtype and float64 rotations,
// validates every number, then rotates without the GIL on the runtime's threads. Shapes,
// broadcasting and rotation forms are the Python half's.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "zhf/dispatch/checks.h"
#include "zhf/dispatch/rotator.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/lobe_table_writer.h"
#include "zhf/runtime/conventions.h"
#include "zhf/runtime/table_io.h"
#include "zhf/runtime/dense_rotation.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/parallel.h"
#include "zhf/runtime/rotation.h"
#include "zhf/sh/analysis.h"
#include "zhf/sh/limits.h"
#include "zhf/tolerances/tolerances.h"

namespace py = pybind11;
namespace rt = zhf::runtime;
namespace zd = zhf::dispatch;

namespace {

template <class T>
using Array = py::array_t<T, py::array::c_style>;

int order_of(const py::buffer_info& coeffs) {
  const auto n = static_cast<std::size_t>(coeffs.shape[1]);
  for (int order = 1; order <= rt::kMaxZxzxzOrder; ++order)
    if (static_cast<std::size_t>(order) * order == n) return order;
  throw rt::InputError("coeffs: a last axis of " + std::to_string(n) + " is not N^2 for an order N <= " +
                       std::to_string(rt::kMaxZxzxzOrder));
}

// Throws InputError naming the first non-finite entry of data[from, total) (vectors of n), if any.
template <class T>
void refuse_non_finite(const T* data, std::size_t from, std::size_t total, std::size_t n) {
  for (std::size_t i = from; i < total; ++i)
    if (!std::isfinite(data[i]))
      throw rt::InputError("coeffs: vector " + std::to_string(i / n) + ", coefficient " + std::to_string(i % n) + ": " +
                           rt::format_number(double(data[i])) + " is not finite");
}

// Rotates count vectors of n coefficients on the runtime's threads, in blocks that stay in cache:
// each block's input is checked for non-finite numbers first, then rotate_block(v, part, in_v,
// out_v) rotates its part vectors from vector v. A non-finite entry is refused, naming the first
// (out is then garbage).
constexpr std::size_t kCheckedBlock = 256;  // vectors: a block's input stays in cache while it is checked and rotated

template <class T, class RotateBlock>
void rotate_checked(const T* in, T* out, std::size_t count, std::size_t n, int threads, const RotateBlock& rotate_block) {
  std::atomic<std::size_t> first_bad_block{count};
  rt::parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end; b += kCheckedBlock) {
      const std::size_t e = std::min(end, b + kCheckedBlock);
      if (!zd::all_finite(in + b * n, (e - b) * n)) {
        std::size_t seen = first_bad_block.load();
        while (b < seen && !first_bad_block.compare_exchange_weak(seen, b)) {
        }
        return;
      }
      rotate_block(b, e - b, in + n * b, out + n * b);
    }
  });
  refuse_non_finite(in, first_bad_block.load() * n, count * n, n);
}

// The caller's output array (the Python half has checked its shape, dtype, layout and that it
// does not overlap the input), or a new one.
template <class T>
Array<T> output_array(std::optional<Array<T>>& into, std::size_t count, std::size_t n) {
  if (!into) return Array<T>({count, n});
  if (into->ndim() != 2 || std::size_t(into->shape(0)) != count || std::size_t(into->shape(1)) != n)
    throw rt::InputError("out: expected the shape of the result");
  return *into;
}

// Refuses anything but an orthogonal matrix (rotations and reflections), naming the vector.
void check_rotation(const double* r, std::size_t v, bool many) {
  const rt::RotationCheck check = rt::validate_rotation(r, zhf::tolerance::kRotationDefect, rt::Handedness::kEither);
  if (!check.ok) throw rt::InputError(std::string("rotation") + (many ? " " + std::to_string(v) : "") + ": " + check.message);
}

template <class T>
Array<T> rotate_shared(const Array<T>& coeffs, const Array<double>& rotation, const rt::LobeTable* table, int threads,
                       std::optional<Array<T>> into) {
  const py::buffer_info in = coeffs.request();
  if (in.ndim != 2) throw rt::InputError("coeffs: expected a (count, N^2) array");
  if (rotation.size() != 9) throw rt::InputError("rotation: expected 9 numbers");
  const int order = order_of(in);
  check_rotation(rotation.data(), 0, false);
  const std::size_t count = in.shape[0], n = in.shape[1];
  Array<T> out = output_array(into, count, n);
  T r[9];
  for (int i = 0; i < 9; ++i) r[i] = T(rotation.data()[i]);
  const T* src = coeffs.data();
  T* dst = out.mutable_data();
  {
    py::gil_scoped_release release;
    const auto prepared = zd::Rotator<T>::make(order, table).prepare(r, count);
    rotate_checked(src, dst, count, n, threads, [&](std::size_t, std::size_t part, const T* f, T* g) { prepared.apply(part, f, g, 1); });
  }
  return out;
}

template <class T>
Array<T> rotate_each(const Array<T>& coeffs, const Array<double>& rotations, const rt::LobeTable* table, int threads,
                     std::optional<Array<T>> into) {
  const py::buffer_info in = coeffs.request();
  if (in.ndim != 2) throw rt::InputError("coeffs: expected a (count, N^2) array");
  const int order = order_of(in);
  const std::size_t count = in.shape[0], n = in.shape[1];
  if (rotations.ndim() != 2 || std::size_t(rotations.shape(0)) != count || rotations.shape(1) != 9)
    throw rt::InputError("rotation: expected one 3x3 matrix per vector");
  Array<T> out = output_array(into, count, n);
  const T* src = coeffs.data();
  T* dst = out.mutable_data();
  const double* r = rotations.data();
  {
    py::gil_scoped_release release;
    for (std::size_t v = 0; v < count; ++v)
      if (!rt::rotation_accepted(r + 9 * v, zhf::tolerance::kRotationDefect, rt::Handedness::kEither)) check_rotation(r + 9 * v, v, true);
    const auto rotator = zd::Rotator<T>::make(order, table);
    rotate_checked(src, dst, count, n, threads, [&](std::size_t v, std::size_t part, const T* f, T* g) {
      if constexpr (std::is_same_v<T, double>) {
        rotator.transform_each(part, r + 9 * v, f, g, 1);
      } else {
        T block[9 * kCheckedBlock];  // the block's rotations in T, converted where they are used
        std::copy(r + 9 * v, r + 9 * (v + part), block);
        rotator.transform_each(part, block, f, g, 1);
      }
    });
  }
  return out;
}

// D_l of R for l < order, each (2l+1, 2l+1): out_l = D_l in_l.
std::vector<Array<double>> band_matrices(const Array<double>& rotation, int order, const rt::LobeTable* table) {
  if (rotation.size() != 9) throw rt::InputError("rotation: expected 9 numbers");
  check_rotation(rotation.data(), 0, false);
  std::vector<Array<double>> bands;
  if (order == 1) {
    Array<double> one({1, 1});
    one.mutable_data()[0] = 1;
    bands.push_back(one);
    return bands;
  }
  const std::vector<std::vector<double>> matrices = zd::Rotator<double>::make(order, table).band_matrices(rotation.data());
  for (int l = 0; l < order; ++l) {
    const auto size = static_cast<std::size_t>(rt::band_size(l));
    Array<double> band({size, size});
    std::copy(matrices[l].begin(), matrices[l].end(), band.mutable_data());
    bands.push_back(band);
  }
  return bands;
}

// (count, 4) quaternions -> ((count, 9) matrices, the largest | |q| - 1 |). Zero or non-finite
// quaternions are refused, naming the first.
py::tuple matrices_from_quaternions(const Array<double>& quaternions, bool scalar_first) {
  if (quaternions.ndim() != 2 || quaternions.shape(1) != 4) throw rt::InputError("rotation: expected (count, 4) quaternions");
  const std::size_t count = quaternions.shape(0);
  Array<double> matrices({count, std::size_t(9)});
  const double* q = quaternions.data();
  double* out = matrices.mutable_data();
  double defect = 0;
  for (std::size_t v = 0; v < count; ++v) {
    const double* c = q + 4 * v;
    const double w = scalar_first ? c[0] : c[3], x = scalar_first ? c[1] : c[0], y = scalar_first ? c[2] : c[1],
                 z = scalar_first ? c[3] : c[2];
    rt::Matrix3 r;
    if (!rt::rotation_from_quaternion(w, x, y, z, r))
      throw rt::InputError("rotation: quaternion " + std::to_string(v) + " is zero or not finite");
    defect = std::max(defect, std::abs(std::sqrt(w * w + x * x + y * y + z * z) - 1));
    std::copy(r.begin(), r.end(), out + 9 * v);
  }
  return py::make_tuple(matrices, defect);
}

const rt::Convention& convention_named(const std::string& name) {
  const rt::Convention* c = rt::find_convention(name);
  if (!c) throw rt::InputError("convention: '" + rt::excerpt(name) + "' is not one of " + rt::convention_names());
  return *c;
}

// (count, 9) rotations written in the convention's axes -> as zhf applies them to its coefficients.
Array<double> rotations_in_zhf_terms(const std::string& name, const Array<double>& rotations) {
  const rt::Convention& c = convention_named(name);
  if (rotations.ndim() != 2 || rotations.shape(1) != 9) throw rt::InputError("rotation: expected (count, 9)");
  const std::size_t count = rotations.shape(0);
  Array<double> out({count, std::size_t(9)});
  for (std::size_t v = 0; v < count; ++v) {
    rt::Matrix3 r;
    std::copy(rotations.data() + 9 * v, rotations.data() + 9 * v + 9, r.begin());
    const rt::Matrix3 z = c.rotation_in_zhf_terms(r);
    std::copy(z.begin(), z.end(), out.mutable_data() + 9 * v);
  }
  return out;
}

// The orthogonal matrix taking coefficients in convention source to convention target.
std::vector<double> conversion(const std::string& source, const std::string& target) {
  const rt::Matrix3 m = rt::multiply(convention_named(target).from_zhf(), convention_named(source).to_zhf());
  return std::vector<double>(m.begin(), m.end());
}

py::dict analyze(const Array<double>& coeffs, double tolerance) {
  const py::buffer_info in = coeffs.request();
  if (in.ndim != 2 || in.shape[0] < 1) throw rt::InputError("coeffs: expected a non-empty (count, N^2) array");
  order_of(in);
  if (!(tolerance >= zhf::sh::kMinZonalTolerance && tolerance <= 1))
    throw rt::InputError("tolerance: must be in [" + rt::format_number(zhf::sh::kMinZonalTolerance) + ", 1]");
  const std::size_t count = in.shape[0], n = in.shape[1];
  refuse_non_finite(coeffs.data(), 0, count * n, n);
  std::vector<Eigen::VectorXd> signals(count);
  for (std::size_t v = 0; v < count; ++v) signals[v] = Eigen::Map<const Eigen::VectorXd>(coeffs.data() + v * n, n);
  const zhf::sh::EnergyReport report = zhf::sh::analyze_energy(signals, tolerance);
  py::dict out;
  out["order"] = report.order;
  out["band_energy"] = report.band_energy;
  out["truncation_error"] = report.truncation_error;
  out["smallest_order"] = report.smallest_order;
  out["zero_bands"] = report.zero_bands;
  return out;
}

py::list table_bands(const rt::LobeTable& table) {
  py::list bands;
  for (const rt::TableBand& band : table.bands) {
    Array<double> inverse({band.inverse.rows, band.inverse.cols});
    std::copy(band.inverse.values.begin(), band.inverse.values.end(), inverse.mutable_data());
    py::dict b;
    b["l"] = band.l;
    b["lobes"] = band.lobes;
    b["inverse"] = inverse;
    b["zeros"] = band.zeros;
    b["condition"] = band.condition;
    bands.append(b);
  }
  return bands;
}

Array<double> table_directions(const rt::LobeTable& table) {
  Array<double> xyz({table.lobes.size(), std::size_t(3)});
  for (std::size_t d = 0; d < table.lobes.size(); ++d)
    for (int i = 0; i < 3; ++i) xyz.mutable_data()[3 * d + i] = table.lobes[d].xyz[i];
  return xyz;
}

}  // namespace

PYBIND11_MODULE(_zhf, m) {
  m.doc() = "zhf's C++ core; use the zhf package, which shapes arrays for it";
  m.attr("__version__") = ZHF_VERSION;
  m.def("isa", [] { return std::string(zd::isa_name(zd::active_isa())); },
        "the instruction-set path rotations take: sse2, avx2 or avx512 on x86-64, neon on aarch64 (ZHF_ISA forces one)");
  m.def("use_isa", &zd::use_isa, py::arg("name"), "forces an instruction-set path the CPU runs for the rotations that follow");
  m.def("isas", [] {
    std::vector<std::string> names;
    for (zd::Isa isa : zd::supported_isas()) names.push_back(zd::isa_name(isa));
    return names;
  }, "the instruction-set paths this CPU runs, fastest first");
  m.def("kernels", [](int order, bool double_precision) {
    return double_precision ? zd::Rotator<double>::make(order).path() : zd::Rotator<float>::make(order).path();
  }, py::arg("order"), py::arg("double_precision"), "the kernels rotations of an order take on isa()'s path");
  m.attr("max_order") = rt::kMaxZxzxzOrder;
  m.attr("max_threads") = rt::kMaxThreads;
  m.attr("default_zonal_fit") = zhf::sh::kDefaultZonalFit;
  // The named tolerances the Python tests hold results to (tolerances/tolerances.h).
  py::dict tolerances;
  tolerances["double"] = zhf::tolerance::kDouble;
  tolerances["float_rotation"] = zhf::tolerance::kFloatRotation;
  tolerances["pointwise"] = zhf::tolerance::kPointwise;
  tolerances["rotation_defect"] = zhf::tolerance::kRotationDefect;
  m.attr("tolerances") = tolerances;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const zhf::io::OutputError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const std::invalid_argument& e) {  // rt::InputError among them
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });

  py::class_<rt::LobeTable>(m, "LobeTable", "A validated lobe table (docs/formats.md); read with read_lobe_table")
      .def_readonly("order", &rt::LobeTable::order)
      .def_readonly("lobe_sharing", &rt::LobeTable::lobe_sharing)
      .def_readonly("zeros", &rt::LobeTable::zeros, "exact zeros of the inverses, all bands")
      .def_readonly("entries", &rt::LobeTable::entries, "entries of the inverses, all bands")
      .def_property_readonly("directions", &table_directions, "the lobe directions, (lobes, 3) unit vectors")
      .def_property_readonly("bands", &table_bands, "per band l >= 2: l, lobes (indices), inverse A_l, zeros, condition")
      .def_property_readonly("worst_condition", &rt::LobeTable::worst_condition)
      .def_property_readonly("command", &rt::provenance_command, "the command that made it (provenance)")
      .def("__repr__", [](const rt::LobeTable& t) {
        return "<zhf.LobeTable order " + std::to_string(t.order) + ", " + std::to_string(t.lobes.size()) + " lobes, " +
               std::to_string(t.zeros) + " zeros of " + std::to_string(t.entries) + ">";
      });

  m.def("read_lobe_table", [](const std::string& path, int order) { return rt::read_lobe_table(path, order); },
        py::arg("path"), py::arg("order") = 0);
  m.def("write_lobe_table", [](const rt::LobeTable& table, const std::string& path) {
          zhf::io::write_file_atomically(path, zhf::io::lobe_table_text(table, path));
        },
        py::arg("table"), py::arg("path"));
  m.def("rotate_shared", &rotate_shared<float>, py::arg("coeffs"), py::arg("rotation"), py::arg("table"), py::arg("threads"),
        py::arg("out").noconvert());
  m.def("rotate_shared", &rotate_shared<double>, py::arg("coeffs"), py::arg("rotation"), py::arg("table"), py::arg("threads"),
        py::arg("out").noconvert());
  m.def("rotate_each", &rotate_each<float>, py::arg("coeffs"), py::arg("rotations"), py::arg("table"), py::arg("threads"),
        py::arg("out").noconvert());
  m.def("rotate_each", &rotate_each<double>, py::arg("coeffs"), py::arg("rotations"), py::arg("table"), py::arg("threads"),
        py::arg("out").noconvert());
  m.def("band_matrices", &band_matrices, py::arg("rotation"), py::arg("order"), py::arg("table"));
  m.def("analyze", &analyze, py::arg("coeffs"), py::arg("tolerance"));
  m.def("rotations_in_zhf_terms", &rotations_in_zhf_terms, py::arg("convention"), py::arg("rotations"));
  m.def("conversion", &conversion, py::arg("source"), py::arg("target"));
  py::list names;
  for (const rt::Convention& c : rt::conventions()) names.append(std::string(c.name));
  m.attr("conventions") = names;
  m.def("matrices_from_quaternions", &matrices_from_quaternions, py::arg("quaternions"), py::arg("scalar_first"));
}
