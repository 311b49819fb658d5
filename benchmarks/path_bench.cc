// Which rotation path is fastest at each generated order, for the instruction set this program is
// compiled for: the measurement behind zhf_kernels.h's choice (generated/paths/<isa>.json, which
// zhf generate turns into gen::fastest_path). For orders 2..8, float and double, every path the
// build has: the scalar kernels; lanes (runtime/lanes.h) where the order has lanes tables; band
// rows and bands 0 and 1 in one register (runtime/band_rows.h) for float where AVX2 and FMA are
// targeted. One rotation per vector (Rotator::rotate_batch over the same random rotations and
// vectors, one thread), the paths alternated within each repetition, the best repetition kept;
// a path other than the scalar kernels is named only where it is more than 3 % faster.
// bench/CMakeLists.txt builds one program per x86-64 instruction set (not built by default):
//   cmake --build build --target zhf_path_bench_avx2
//   build/benchmarks/zhf_path_bench_avx2 [--write generated/paths/avx2.json] [--rotations 1024] [--reps 101]
// then `zhf generate` and commit both. Emulated runs (qemu) time nothing meaningful: write no table
// from one.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "zhf/bench/machine.h"
#include "zhf/io/files.h"
#include "zhf/runtime/rotator.h"
#include "zhf/sh/random.h"
#include "zhf/sh/rotation_matrix.h"
#include "zhf_kernels.h"

namespace {

using zhf::runtime::KernelSet;

// Another path is named fastest only when it beats the scalar kernels by more than this factor:
// near-ties flip from run to run (order 4 on baseline x86-64: lanes 36.2 against 37.9 ns in one
// run, the other way in the next), and the scalar kernels are the simplest code.
constexpr double kBeatScalarBy = 1.03;

struct Options {
  std::string write;
  std::size_t rotations = 1024;
  int reps = 101;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int k = 1; k < argc; ++k) {
    const bool has_value = k + 1 < argc;
    if (std::strcmp(argv[k], "--write") == 0 && has_value) {
      o.write = argv[++k];
    } else if (std::strcmp(argv[k], "--rotations") == 0 && has_value) {
      o.rotations = std::size_t(std::max(1L, std::atol(argv[++k])));
    } else if (std::strcmp(argv[k], "--reps") == 0 && has_value) {
      o.reps = std::max(1, std::atoi(argv[++k]));
    } else {
      std::fprintf(stderr, "zhf_path_bench: usage: [--write FILE] [--rotations N] [--reps N]\n");
      std::exit(2);
    }
  }
  return o;
}

// Every path this build has for order N in T.
template <int N, class T>
std::vector<KernelSet<T>> candidates() {
  std::vector<KernelSet<T>> out = {zhf::runtime::scalar_kernels<N, T>()};
  if constexpr (zhf::gen::kHasLanes<N>) out.push_back(zhf::runtime::lanes_kernels<N, T>());
  if constexpr (zhf::runtime::kBandRowsBuilt && std::is_same_v<T, float>) {
    if constexpr (N == 2) out.push_back(zhf::runtime::bands01_kernels());
    if constexpr (N >= zhf::runtime::kBandRowsMinOrder && N <= zhf::runtime::kBandRowsMaxOrder)
      out.push_back(zhf::runtime::band_rows_kernels<N>());
  }
  return out;
}

// {"fastest": path, "ns": {path: ns per rotation}} for order N in T.
template <int N, class T>
nlohmann::ordered_json time_paths(const Options& o) {
  const std::vector<KernelSet<T>> paths = candidates<N, T>();
  std::mt19937_64 rng(N);
  zhf::sh::Normal<T> normal;
  std::vector<T> r(9 * o.rotations), in(N * N * o.rotations), out(N * N * o.rotations);
  for (std::size_t v = 0; v < o.rotations; ++v) {
    const zhf::sh::RotationMatrix m = zhf::sh::random_rotation(rng);
    for (int k = 0; k < 9; ++k) r[9 * v + k] = T(m(k / 3, k % 3));
  }
  for (T& x : in) x = normal(rng);
  std::vector<double> best(paths.size(), 1e30);
  for (int rep = 0; rep < o.reps; ++rep)
    for (std::size_t p = 0; p < paths.size(); ++p) {
      const auto rotator = zhf::runtime::Rotator<T>::with(paths[p]);
      const auto start = std::chrono::steady_clock::now();
      rotator.rotate_batch(o.rotations, r.data(), in.data(), out.data(), 1);
      best[p] = std::min(best[p], std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
  nlohmann::ordered_json ns = nlohmann::ordered_json::object();
  std::size_t fastest = 0;  // the scalar kernels
  for (std::size_t p = 0; p < paths.size(); ++p) {
    ns[paths[p].path] = std::round(best[p] / o.rotations * 1e12) / 1e3;
    if (best[p] * kBeatScalarBy < best[0] && best[p] < best[fastest]) fastest = p;
  }
  return {{"fastest", paths[fastest].path}, {"ns", ns}};
}

template <int N>
nlohmann::ordered_json time_order(const Options& o) {
  return {{"order", N}, {"float", time_paths<N, float>(o)}, {"double", time_paths<N, double>(o)}};
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  nlohmann::ordered_json orders = nlohmann::ordered_json::array();
  orders.push_back(time_order<2>(o));
  orders.push_back(time_order<3>(o));
  orders.push_back(time_order<4>(o));
  orders.push_back(time_order<5>(o));
  orders.push_back(time_order<6>(o));
  orders.push_back(time_order<7>(o));
  orders.push_back(time_order<8>(o));
  const std::string measured_on = zhf::bench::cpu_model() + ", g++ " + __VERSION__ + " " + ZHF_PATH_BENCH_FLAGS + ", " + zhf::bench::today() + ", " +
                                  std::to_string(o.rotations) + " rotations, best of " + std::to_string(o.reps);
  const nlohmann::ordered_json table = {
      {"format", "zhf-paths-1"}, {"isa", zhf::gen::kBuildIsa}, {"measured_on", measured_on}, {"orders", orders}};
  const std::string text = zhf::io::json_text(table);
  std::printf("%s", text.c_str());
  if (!o.write.empty()) zhf::io::write_file_atomically(o.write, text);
  return 0;
}
