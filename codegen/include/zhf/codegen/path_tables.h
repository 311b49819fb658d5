// The measured path tables zhf_kernels.h is generated from: generated/paths/<isa>.json, one per
// instruction set ("sse2", "avx2", "avx512", "neon"), written by benchmarks/path_bench.cc built for
// that instruction set (zhf_path_bench_<isa> --write). Each names, for every generated order and
// for float and double, the rotation path that was fastest there, with the times behind it.
#pragma once

#include <string>
#include <vector>

namespace zhf::codegen {

enum class RotationPath { kScalar, kLanes, kBandRows, kBands01 };

// "scalar", "lanes", "band_rows", "bands01": the names KernelSet::path gives them.
const char* rotation_path_name(RotationPath path);

struct PathTimes {
  RotationPath fastest = RotationPath::kScalar;     // of every path timed
  std::vector<std::pair<RotationPath, double>> ns;  // ns per rotation of each path timed
};

struct OrderPaths {
  int order = 0;
  PathTimes float_paths, double_paths;
};

struct PathTable {
  std::string isa;          // "avx2", ...
  std::string file;         // as read
  std::string measured_on;  // "CPU, compiler flags, date, what was timed": printable text
  std::vector<OrderPaths> orders;
};

// The instruction sets a table may be written for, in the order zhf_kernels.h tests for them.
const std::vector<std::string>& path_table_isas();

// The tables present in dir (<isa>.json for each of path_table_isas(); none if dir is empty or
// holds none), each checked on its own terms: orders runtime::kMinGeneratedOrder..kMaxGeneratedOrder,
// each at most once, and only paths its instruction set, type and order can have (lanes from
// order 3; band rows and bands 0 and 1 in one register for float with AVX2, orders 4..8 and 2).
// They were measured on zhf's own lobe tables; a tree made from other tables takes them as they
// are, for the paths it has (fastest_available). Throws io::InputError naming the file and field.
std::vector<PathTable> read_path_tables(const std::string& dir);

// The fastest timed path of `times` that a tree has: lanes only where it has lanes tables for the
// order; the scalar kernels when it has none of them.
RotationPath fastest_available(const PathTimes& times, bool has_lanes);

}  // namespace zhf::codegen
