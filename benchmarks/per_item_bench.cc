// Per-item rotations (each vector its own rotation, the usual layout: R[9 v + k], in[N^2 v + i])
// two ways side by side in one run, per order and type: the fastest kernel set's own batch
// (gen::fastest_kernels<N, T>().rotate_batch: the set's kernel vector by vector) and the SoA
// blocks (runtime::rotate_items<N, T>: kLanes vectors transposed into packs, the generated kernel
// on packs, transposed back). One thread; the best of the runs in ns per vector; the largest
// difference between the two. This is the measurement behind zhf::dispatch's choice of per-item
// batch (dispatch/src/isa_unit.h). Built for each instruction set by benchmarks/per_item.sh:
//   g++ -O3 -march=x86-64-v3 -DNDEBUG -std=c++17 -Iruntime/include -Igenerated/cpp -Ish/include benchmarks/per_item_bench.cc
//   per_item_bench [runs=15]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "zhf/runtime/rotation.h"
#include "zhf/runtime/soa_batch.h"
#include "zhf/sh/random.h"
#include "zhf_kernels.h"

namespace {

using zhf::sh::Rng;

template <class Call>
double best_ns(int runs, std::size_t count, const Call& call) {
  double best = 1e300;
  for (int run = 0; run < runs; ++run) {
    const auto start = std::chrono::steady_clock::now();
    call();
    best = std::min(best, std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count() / double(count));
  }
  return best;
}

template <int N, class T>
void row(std::size_t count, int runs) {
  constexpr std::size_t n = std::size_t(N) * N;
  Rng rng(N);
  std::vector<T> r(9 * count), in(n * count), batch(n * count), items(n * count);
  for (std::size_t v = 0; v < count; ++v) {
    double q[4], norm = 0;
    for (double& x : q) x = 2 * zhf::sh::uniform01(rng) - 1, norm += x * x;
    zhf::runtime::Matrix3 m;
    zhf::runtime::rotation_from_quaternion(q[0], q[1], q[2], q[3], m);
    for (int k = 0; k < 9; ++k) r[9 * v + k] = T(m[k]);
  }
  for (T& x : in) x = T(2 * zhf::sh::uniform01(rng) - 1);
  const auto kernels = zhf::gen::fastest_kernels<N, T>();
  const double own = best_ns(runs, count, [&] { kernels.rotate_batch(count, r.data(), in.data(), batch.data()); });
  const double lanes = best_ns(runs, count, [&] { zhf::runtime::rotate_items<N, T>(count, r.data(), in.data(), items.data()); });
  double diff = 0;
  for (std::size_t i = 0; i < batch.size(); ++i) diff = std::max(diff, double(std::abs(batch[i] - items[i])));
  std::printf("%-6s  %d  %7zu  %-9s  %8.2f  %8.2f  %5.2f  %.2g\n", sizeof(T) == 4 ? "float" : "double", N, count, kernels.path, own, lanes,
              own / lanes, diff);
}

template <class T>
void rows(std::size_t count, int runs) {
  row<2, T>(count, runs), row<3, T>(count, runs), row<4, T>(count, runs), row<5, T>(count, runs);
  row<6, T>(count, runs), row<7, T>(count, runs), row<8, T>(count, runs);
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 15;
  std::printf("type    N  vectors  own path   own ns    items ns  own/items  max diff\n");
  for (std::size_t count : {std::size_t(4096), std::size_t(200000)}) {
    rows<float>(count, runs);
    rows<double>(count, runs);
  }
}
