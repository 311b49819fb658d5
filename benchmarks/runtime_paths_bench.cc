// The two run-time paths of Rotator::from_table side by side in one run, per order: the lobe path
// (runtime/table_rotation.h) and zxzxz (runtime/zxzxz_rotation.h), float, one vector per call,
// each with its own random rotation, median of the runs; max error against the double lobe path.
// This is the measurement behind kZxzxzFromOrder. Build for the ISA to report, e.g.
//   g++ -O3 -march=x86-64-v3 -DNDEBUG -std=c++17 -Iruntime/include -Igenerated/cpp benchmarks/runtime_paths_bench.cc
//   zhf_runtime_paths_bench [tables=generated/lobes] [runs=15]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <random>
#include <string>
#include <vector>

#include "zhf/runtime/table_io.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/table_rotation.h"
#include "zhf/runtime/zxzxz_rotation.h"
#include "zhf/sh/random.h"

int main(int argc, char** argv) {
  using namespace zhf::runtime;
  const std::string tables = argc > 1 ? argv[1] : "generated/lobes";
  const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 15;
  const int count = 256;
  std::printf("order  lobe path ns  zxzxz ns  lobe/zxzxz  lobe err  zxzxz err\n");
  for (int order : {3, 4, 5, 6, 7, 8, 9, 10, 12, 16, 32}) {
    LobeTable table;
    try {
      table = read_lobe_table(table_path(tables, order));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "zhf_runtime_paths_bench: %s\n", e.what());
      return 2;
    }
    const TableRotation<float> lobes(table);
    const TableRotation<double> exact(table);
    const ZxzxzRotation<float> zxzxz(order);
    const int n = order * order;
    std::mt19937_64 rng(order);
    zhf::sh::Normal<> normal;
    std::vector<float> r(9 * count), in(n * count), out(n * count);
    std::vector<double> rd(9 * count), ind(n * count), expected(n * count);
    for (int v = 0; v < count; ++v) {
      double axis[3] = {normal(rng), normal(rng), normal(rng)};
      const double length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
      for (double& a : axis) a /= length;
      const Matrix3 m = rotation_about_unit_axis(axis, 3 * normal(rng));
      for (int k = 0; k < 9; ++k) r[9 * v + k] = float(m[k]), rd[9 * v + k] = r[9 * v + k];
      double norm = 0;
      for (int i = 0; i < n; ++i) ind[n * v + i] = normal(rng), norm += ind[n * v + i] * ind[n * v + i];
      for (int i = 0; i < n; ++i) in[n * v + i] = float(ind[n * v + i] / std::sqrt(norm)), ind[n * v + i] = in[n * v + i];
      exact.rotate(&rd[9 * v], &ind[n * v], &expected[n * v], 1);
    }
    auto measure = [&](auto&& rotate, double& error) {
      std::vector<double> ns;
      for (int run = 0; run < runs; ++run) {
        const auto start = std::chrono::steady_clock::now();
        for (int v = 0; v < count; ++v) rotate(&r[9 * v], &in[n * v], &out[n * v]);
        ns.push_back(std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count() / count);
      }
      error = 0;
      for (int i = 0; i < n * count; ++i) error = std::max(error, std::fabs(double(out[i]) - expected[i]));
      std::sort(ns.begin(), ns.end());
      return ns[ns.size() / 2];
    };
    double lobe_error = 0, zxzxz_error = 0;
    const double lobe_ns = measure([&](const float* rv, const float* f, float* g) { lobes.rotate(rv, f, g, 1); }, lobe_error);
    const double zxzxz_ns = measure([&](const float* rv, const float* f, float* g) { zxzxz.rotate(rv, f, g, 1); }, zxzxz_error);
    std::printf("%5d  %12.0f  %8.0f  %10.2f  %8.1e  %9.1e\n", order, lobe_ns, zxzxz_ns, lobe_ns / zxzxz_ns, lobe_error, zxzxz_error);
  }
  return 0;
}
