#include "zhf/codegen/dispatch.h"

#include <algorithm>
#include <sstream>

#include "c_family_printer.h"

namespace zhf::codegen {
namespace {

// Where the lobe-parallel kernel (runtime/lanes.h) is the faster path for one vector per rotation,
// float, against the scalar kernels (order 3 by its quadratic form, zxzxz at 4..8), as measured by
// the peer harness (one run, median ns, AMD EPYC Zen 3 class, g++ 12 -O3; docs/performance.md):
//   x86-64-v3 (AVX2, FMA), lanes / scalar: N=3 12.7/6.8, 4 22.3/28.6, 5 44.8/43.1, 6 82.6/62.8, 7 185.5/88.7, 8 275.1/120.8
//   x86-64 baseline (SSE2), lanes / scalar: N=3 15.3/7.6, 4 28.4/30.6, 5 76.1/47.1
// (order 5 with AVX2 went to the scalar kernel in two runs out of three). Other architectures were
// not measured, so they keep the scalar kernels. Where AVX2 and FMA are targeted, lanes.h holds
// order 4's float kernel in one register of lobes, in intrinsics: 21.2 ns against the band rows'
// 30.4 ns and the scalar kernel's 41.6 ns (1024 random rotations, median of 31 alternating runs,
// AMD EPYC, g++ 12 -O3 -march=x86-64-v3).
constexpr int kLanesFrom = 4;
constexpr int kLanesUpToX86 = 4;
constexpr const char* kMeasuredOn = "x86-64: lanes at order 4, with AVX2 and on baseline SSE2";
// Where the band-rows kernel (runtime/band_rows.h: float, built only for AVX2 and FMA) is the
// faster path for one float vector per rotation, against the scalar kernels and lanes, in one
// process (1024 random rotations, min ns of 31 alternating runs, AMD EPYC, g++ 12 -O3
// -march=x86-64-v3), band rows / scalar: N=4 31.4/40.6 (lanes 35.5), 5 44.3/54.1, 6 55.0/77.3,
// 7 67.2/127.8, 8 83.2/175.4; the peer harness's run is in docs/performance.md. Order 4 goes to
// lanes (above). Order 2 (bands 0 and 1 in one register, band_rows.h's bands01_kernels) against
// the scalar kernel, same build, K = 1024: 0.97 against 1.90 ns.
constexpr int kBandRowsFrom = 5;

std::string list(const std::vector<int>& values) {
  std::string out;
  for (int v : values) out += (out.empty() ? "" : ", ") + std::to_string(v);
  return out;
}

}  // namespace

EmittedFile emit_dispatch_header(const std::vector<int>& orders, const std::vector<int>& lanes_orders,
                                 const std::string& command) {
  std::ostringstream out;
  out << banner(command, {}) << "//   (none: dispatch only)\n";
  out << "// Every generated order (" << list(orders) << ") reachable at run time, and the fastest verified\n"
      << "// rotation path of each for the instruction set this header is compiled for.\n";
  out << "#pragma once\n\n#include <stdexcept>\n#include <string>\n#include <type_traits>\n\n";
  out << "#include \"zhf/runtime/band_rows.h\"\n#include \"zhf/runtime/lanes.h\"\n#include \"zhf/runtime/rotator.h\"\n";
  for (int n : orders) out << "#include \"zhf_order" << n << ".h\"\n";
  for (int n : lanes_orders) out << "#include \"zhf_lanes_order" << n << ".h\"\n";
  out << "\nnamespace zhf::gen {\n\n";
  out << "// Calls f(std::integral_constant<int, N>{}) for the generated order N equal to order; throws\n"
      << "// std::invalid_argument for any other order.\n"
      << "template <class F>\ndecltype(auto) with_order(int order, F&& f) {\n  switch (order) {\n";
  for (int n : orders) out << "    case " << n << ": return f(std::integral_constant<int, " << n << ">{});\n";
  out << "    default: break;\n  }\n"
      << "  throw std::invalid_argument(\"zhf: order \" + std::to_string(order) + \" has no generated kernels (" << list(orders)
      << ")\");\n}\n\n";
  out << "// Whether order N has lanes tables (zhf_lanes_orderN.h).\n"
      << "template <int N>\ninline constexpr bool kHasLanes = false;\n";
  for (int n : lanes_orders) out << "template <>\ninline constexpr bool kHasLanes<" << n << "> = true;\n";
  out << "\n// Where runtime/lanes.h is the faster verified path, by measurement: " << kMeasuredOn << ";\n"
      << "// other architectures unmeasured (the scalar kernels). docs/performance.md has the figures.\n"
      << "#if defined(__x86_64__) || defined(_M_X64)\ninline constexpr int kLanesUpTo = " << kLanesUpToX86 << ";\n#else\n"
      << "inline constexpr int kLanesUpTo = 0;\n#endif\ninline constexpr int kLanesFrom = " << kLanesFrom << ";\n\n";
  out << "// Where runtime/band_rows.h is the faster verified path for float, by measurement: order 2 (bands 0\n"
      << "// and 1 in one register) and from this order to its last (runtime::kBandRowsMaxOrder), in builds\n"
      << "// that have it (runtime::kBandRowsBuilt).\n"
      << "inline constexpr int kBandRowsFrom = " << kBandRowsFrom << ";\n\n";
  out << "// The fastest verified rotation path of generated order N. One branch is instantiated per order\n"
      << "// and type: only the kernels chosen are compiled.\n"
      << "template <int N, class T>\nruntime::KernelSet<T> fastest_kernels() {\n"
      << "  constexpr bool band_rows = std::is_same_v<T, float> && runtime::kBandRowsBuilt;\n"
      << "  if constexpr (band_rows && N == 2) {\n"
      << "    return runtime::bands01_kernels();\n"
      << "  } else if constexpr (band_rows && N >= kBandRowsFrom && N <= runtime::kBandRowsMaxOrder) {\n"
      << "    return runtime::band_rows_kernels<N>();\n"
      << "  } else if constexpr (kHasLanes<N> && N >= kLanesFrom && N <= kLanesUpTo) {\n"
      << "    return runtime::lanes_kernels<N, T>();\n"
      << "  } else {\n"
      << "    return runtime::scalar_kernels<N, T>();\n"
      << "  }\n}\n\n";
  out << "// The same for an order chosen at run time: every generated order's kernels are compiled (throws\n"
      << "// for any other order).\n"
      << "template <class T>\nruntime::KernelSet<T> fastest_kernels(int order) {\n"
      << "  return with_order(order, [](auto n) { return fastest_kernels<decltype(n)::value, T>(); });\n}\n\n";
  out << "// The fastest rotator of any order 1..runtime::kMaxZxzxzOrder for the instruction set this header\n"
      << "// is compiled for: the generated orders' fastest kernels, runtime::Rotator::zxzxz elsewhere.\n"
      << "// Throws std::invalid_argument for any other order. (zhf::dispatch::Rotator<T>::make picks among\n"
      << "// instruction sets at run time.)\n"
      << "template <class T>\nruntime::Rotator<T> fastest_rotator(int order) {\n"
      << "  if (order >= " << orders.front() << " && order <= " << orders.back() << ") return runtime::Rotator<T>::with(fastest_kernels<T>(order));\n"
      << "  return runtime::Rotator<T>::zxzxz(order);\n}\n\n";
  out << "// The generated scalar kernels of an order chosen at run time.\n"
      << "template <class T>\nruntime::KernelSet<T> scalar_kernels(int order) {\n"
      << "  return with_order(order, [](auto n) { return runtime::scalar_kernels<decltype(n)::value, T>(); });\n}\n\n";
  out << "}  // namespace zhf::gen\n";
  return {"zhf_kernels.h", out.str(), {}};
}

}  // namespace zhf::codegen
