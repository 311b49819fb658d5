#include "zhf/codegen/path_headers.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "c_family_printer.h"

namespace zhf::codegen {
namespace {

// The preprocessor test for a build of each instruction set a table may be written for, in the
// order path_table_isas() lists them (the first that holds wins).
std::string build_test(const std::string& isa) {
  if (isa == "avx512") return "defined(__AVX512F__) && ZHF_RUNTIME_AVX2_FMA";
  if (isa == "avx2") return "ZHF_RUNTIME_AVX2_FMA";
  if (isa == "sse2") return "defined(__x86_64__) || defined(_M_X64)";
  return "defined(__aarch64__)";
}

// The table a build for isa follows: its own, else that of the instruction set below it whose
// kernels it runs (avx512 -> avx2 -> sse2), else none (the scalar kernels).
const PathTable* table_for(const std::string& isa, const std::vector<PathTable>& tables) {
  const std::vector<std::string> chain = isa == "avx512" ? std::vector<std::string>{"avx512", "avx2", "sse2"}
                                         : isa == "avx2" ? std::vector<std::string>{"avx2", "sse2"}
                                                         : std::vector<std::string>{isa};
  for (const std::string& candidate : chain)
    for (const PathTable& t : tables)
      if (t.isa == candidate) return &t;
  return nullptr;
}

std::string path_enum(RotationPath p) {
  switch (p) {
    case RotationPath::kScalar: return "Path::kScalar";
    case RotationPath::kLanes: return "Path::kLanes";
    case RotationPath::kBandRows: return "Path::kBandRows";
    case RotationPath::kBands01: return "Path::kBands01";
  }
  return "Path::kScalar";
}

// The path chosen, then each path's time.
std::string times_text(RotationPath chosen, const PathTimes& t) {
  std::string out = rotation_path_name(chosen);
  out += " (";
  for (size_t k = 0; k < t.ns.size(); ++k) {
    char value[32];
    std::snprintf(value, sizeof value, "%.3g", t.ns[k].second);
    out += (k ? ", " : "") + std::string(rotation_path_name(t.ns[k].first)) + " " + value;
  }
  return out + ")";
}

// Path, kBuildIsa and fastest_path<T>(order) for each instruction set, from its table: for each
// order of the tree, the fastest path measured there that the tree has.
std::string path_choice(const std::vector<PathTable>& tables, const std::vector<int>& orders, const std::vector<int>& lanes_orders) {
  std::ostringstream out;
  out << "// The rotation path of each generated order, by instruction set, from the measured tables in\n"
      << "// generated/paths (benchmarks/path_bench.cc writes them, zhf generate turns them into what follows); a\n"
      << "// build whose instruction set has no table follows the one below it whose kernels it runs, or,\n"
      << "// with none, the scalar kernels. The tables were measured on zhf's own lobe tables; each order\n"
      << "// takes the fastest path measured there that this tree has (lanes only with lanes tables).\n"
      << "enum class Path { kScalar, kLanes, kBandRows, kBands01 };\n\n"
      << "// The name KernelSet::path gives a path.\n"
      << "constexpr const char* path_name(Path path) {\n"
      << "  return path == Path::kLanes ? \"lanes\" : path == Path::kBandRows ? \"band_rows\" : path == Path::kBands01 ? \"bands01\" : \"scalar\";\n"
      << "}\n\n";
  const std::vector<std::string>& isas = path_table_isas();
  for (size_t k = 0; k < isas.size(); ++k) {
    const std::string& isa = isas[k];
    out << (k == 0 ? "#if " : "#elif ") << build_test(isa) << "\n";
    out << "inline constexpr char kBuildIsa[] = \"" << isa << "\";\n";
    const PathTable* table = table_for(isa, tables);
    if (!table) {
      out << "// " << isa << ": no table measured; the scalar kernels.\n"
          << "template <class T>\nconstexpr Path fastest_path(int) {\n  return Path::kScalar;\n}\n";
      continue;
    }
    out << "// " << isa << ": " << (table->isa == isa ? "" : "no table of its own; " + table->isa + "'s, ")
        << "generated/paths/" << table->isa << ".json, measured on\n// " << comment_text(table->measured_on) << ".\n"
        << "// The path taken, with each path's ns per rotation, float; double:\n";
    std::ostringstream cases;
    for (int order : orders) {
      const auto o = std::find_if(table->orders.begin(), table->orders.end(), [&](const OrderPaths& p) { return p.order == order; });
      if (o == table->orders.end()) {
        out << "//   order " << order << ": not measured; scalar\n";
        continue;
      }
      const bool has_lanes = std::find(lanes_orders.begin(), lanes_orders.end(), order) != lanes_orders.end();
      const RotationPath f = fastest_available(o->float_paths, has_lanes), d = fastest_available(o->double_paths, has_lanes);
      out << "//   order " << order << ": " << times_text(f, o->float_paths) << "; " << times_text(d, o->double_paths) << "\n";
      if (f == RotationPath::kScalar && d == RotationPath::kScalar) continue;
      cases << "    case " << order << ": return ";
      if (f == d) cases << "is_float || is_double ? " << path_enum(f) << " : Path::kScalar;\n";
      else if (d == RotationPath::kScalar) cases << "is_float ? " << path_enum(f) << " : Path::kScalar;\n";
      else cases << "is_float ? " << path_enum(f) << " : is_double ? " << path_enum(d) << " : Path::kScalar;\n";
    }
    out << "template <class T>\nconstexpr Path fastest_path(int order) {\n"
        << "  [[maybe_unused]] constexpr bool is_float = std::is_same_v<T, float>, is_double = std::is_same_v<T, double>;\n"
        << "  switch (order) {\n"
        << cases.str();
    out << "    default: return Path::kScalar;\n  }\n}\n";
  }
  out << "#else\ninline constexpr char kBuildIsa[] = \"generic\";\n"
      << "template <class T>\nconstexpr Path fastest_path(int) {\n  return Path::kScalar;\n}\n#endif\n\n";
  return out.str();
}

std::string list(const std::vector<int>& values) {
  std::string out;
  for (int v : values) out += (out.empty() ? "" : ", ") + std::to_string(v);
  return out;
}

}  // namespace

EmittedFile emit_paths_header(const std::vector<int>& orders, const std::vector<int>& lanes_orders, const std::vector<PathTable>& tables,
                              const std::string& command) {
  std::ostringstream out;
  out << banner(command, {}) << "//   (none: the path choice only)\n";
  out << "// The fastest verified rotation path of each generated order (" << list(orders) << ")\n"
      << "// for the instruction set this header is compiled for, and the kernels and rotator of one order\n"
      << "// on it. Include it with the orders you use (zhf_orderN.h); zhf_kernels.h includes it with\n"
      << "// every order.\n";
  out << "#pragma once\n\n#include <type_traits>\n\n";
  out << "#include \"zhf/runtime/band_rows.h\"\n#include \"zhf/runtime/lanes.h\"\n#include \"zhf/runtime/rotator.h\"\n";
  out << "// The lanes path's tables: constants only, a few kilobytes an order.\n";
  for (int n : lanes_orders) out << "#include \"zhf_lanes_order" << n << ".h\"\n";
  out << "\nnamespace zhf::gen {\n\n";
  out << "// Whether order N has lanes tables (zhf_lanes_orderN.h).\n"
      << "template <int N>\ninline constexpr bool kHasLanes = false;\n";
  for (int n : lanes_orders) out << "template <>\ninline constexpr bool kHasLanes<" << n << "> = true;\n";
  out << "\n" << path_choice(tables, orders, lanes_orders);
  out << "// The fastest verified rotation path of generated order N (its zhf_orderN.h included). One\n"
      << "// branch is instantiated per order and type: only the kernels chosen are compiled.\n"
      << "template <int N, class T>\nruntime::KernelSet<T> fastest_kernels() {\n"
      << "  constexpr Path path = fastest_path<T>(N);\n"
      << "  if constexpr (path == Path::kBands01) {\n"
      << "    return runtime::bands01_kernels();\n"
      << "  } else if constexpr (path == Path::kBandRows) {\n"
      << "    return runtime::band_rows_kernels<N>();\n"
      << "  } else if constexpr (path == Path::kLanes) {\n"
      << "    return runtime::lanes_kernels<N, T>();\n"
      << "  } else {\n"
      << "    return runtime::scalar_kernels<N, T>();\n"
      << "  }\n}\n\n";
  out << "// A rotator of generated order N on that path.\n"
      << "template <int N, class T>\nruntime::Rotator<T> fastest_rotator() {\n"
      << "  return runtime::Rotator<T>::with(fastest_kernels<N, T>());\n}\n\n";
  out << "}  // namespace zhf::gen\n";
  return {"zhf_paths.h", out.str(), {}};
}

EmittedFile emit_dispatch_header(const std::vector<int>& orders, const std::string& command) {
  std::ostringstream out;
  out << banner(command, {}) << "//   (none: dispatch only)\n";
  out << "// Every generated order (" << list(orders) << ") reachable at run time, on the fastest verified\n"
      << "// rotation path of each for the instruction set this header is compiled for (zhf_paths.h).\n";
  out << "#pragma once\n\n#include <stdexcept>\n#include <string>\n#include <type_traits>\n\n";
  for (int n : orders) out << "#include \"zhf_order" << n << ".h\"\n";
  out << "#include \"zhf_paths.h\"\n";
  out << "\nnamespace zhf::gen {\n\n";
  out << "// Calls f(std::integral_constant<int, N>{}) for the generated order N equal to order; throws\n"
      << "// std::invalid_argument for any other order.\n"
      << "template <class F>\ndecltype(auto) with_order(int order, F&& f) {\n  switch (order) {\n";
  for (int n : orders) out << "    case " << n << ": return f(std::integral_constant<int, " << n << ">{});\n";
  out << "    default: break;\n  }\n"
      << "  throw std::invalid_argument(\"zhf: order \" + std::to_string(order) + \" has no generated kernels (" << list(orders)
      << ")\");\n}\n\n";
  out << "// fastest_kernels<N, T>() for an order chosen at run time: every generated order's kernels are\n"
      << "// compiled (throws for any other order).\n"
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
