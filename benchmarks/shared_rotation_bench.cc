// The C++ batch path that zhf.rotate's one-rotation case runs: count vectors of channels x N^2
// floats under one rotation (Rotator::rotate_shared, fastest kernels, all cores), the reference
// for the Python binding's overhead (benchmarks/python_bench.py). Prints one JSON object with the
// median and minimum seconds over the runs. fresh=1 rotates into a newly allocated output each
// run (what a call returning a new array pays: the first touch of its pages), timed with it.
//   zhf_shared_rotation_bench [order=4] [vectors=1000000] [channels=3] [runs=7] [threads=0] [fresh=0]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <vector>

#include "zhf/runtime/limits.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/rotator.h"
#include "zhf/sh/random.h"
#include "zhf_kernels.h"

int main(int argc, char** argv) {
  auto arg = [&](int i, long fallback) { return argc > i ? std::atol(argv[i]) : fallback; };
  const int order = int(arg(1, 4));
  const std::size_t vectors = std::size_t(arg(2, 1000000)), channels = std::size_t(arg(3, 3));
  const int runs = int(arg(4, 7)), threads = int(arg(5, 0));
  const bool fresh = arg(6, 0) != 0;
  if (order < 2 || order > zhf::runtime::kMaxGeneratedOrder || vectors < 1 || channels < 1 || runs < 1 || threads < 0) {
    std::fprintf(stderr, "zhf_shared_rotation_bench: arguments out of range\n");
    return 2;
  }
  const std::size_t count = vectors * channels, n = std::size_t(order) * order;
  std::vector<float> in(count * n), reused(count * n);
  std::mt19937_64 rng(1);
  zhf::sh::Normal<float> normal;
  for (float& x : in) x = normal(rng);
  const double axis[3] = {0.48, 0.6, 0.64};
  const zhf::runtime::Matrix3 r = zhf::runtime::rotation_about_unit_axis(axis, 1.1);
  float rf[9];
  for (int i = 0; i < 9; ++i) rf[i] = float(r[i]);
  const auto rotator = zhf::runtime::Rotator<float>::with(zhf::gen::fastest_kernels<float>(order));
  std::vector<double> seconds;
  float checksum = 0;
  for (int run = 0; run < runs; ++run) {
    const auto start = std::chrono::steady_clock::now();
    std::unique_ptr<float[]> allocated(fresh ? new float[count * n] : nullptr);  // not zeroed: untouched pages
    float* out = fresh ? allocated.get() : reused.data();
    rotator.rotate_shared(count, rf, in.data(), out, threads);
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    checksum = out[count * n / 2];
  }
  std::sort(seconds.begin(), seconds.end());
  std::printf("{\"order\": %d, \"vectors\": %zu, \"channels\": %zu, \"threads\": %d, \"median_s\": %.6f, \"min_s\": %.6f, "
              "\"fresh\": %d, \"checksum\": %.6g}\n",
              order, vectors, channels, threads, seconds[seconds.size() / 2], seconds.front(), int(fresh), double(checksum));
  return 0;
}
