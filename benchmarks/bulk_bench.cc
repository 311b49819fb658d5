// The bulk paths against this machine's memory bandwidth, in one run:
//   copy       STREAM-style copy (memcpy of the same bytes, split over the same threads): the ceiling;
//   splats     one rotation for many 3DGS items (DC RGB, then bands 1.. of R, G, B: 3 N^2 floats
//              each), DenseRotation::apply_splats;
//   planar     the same items as planes of one coefficient of one channel each, apply_planar;
//   soa        many rotations, one per vector, structure of arrays: runtime::rotate_soa (the
//              generated kernel across SIMD lanes), the generated rotate_batch_orderN loop, and
//              the scalar kernel called once per rotation.
// Rates count bytes read plus bytes written; "of copy" is the rate over the copy's in that run.
// Out of place, each written line is first read (write-allocate), a third more traffic than the
// copy's; in place it is not.
// Build for the ISA to report (bench/CMakeLists.txt builds it with the project's flags), e.g.
//   g++ -O3 -march=x86-64-v3 -DNDEBUG -std=c++17 -Iruntime/include -Ish/include -Igenerated/cpp benchmarks/bulk_bench.cc -pthread
//   zhf_bulk_bench [items=1048576] [runs=7]
#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <thread>
#include <vector>

#include "zhf/runtime/rotation.h"
#include "zhf/runtime/rotator.h"
#include "zhf/runtime/soa_batch.h"
#include "zhf/sh/random.h"
#include "zhf_kernels.h"

namespace {

using Clock = std::chrono::steady_clock;

template <class Work>
double best_seconds(int runs, Work&& work) {
  double best = 1e30;
  for (int run = 0; run < runs; ++run) {
    const auto start = Clock::now();
    work();
    best = std::min(best, std::chrono::duration<double>(Clock::now() - start).count());
  }
  return best;
}

void copy(const float* in, float* out, std::size_t count, int threads) {
  zhf::runtime::parallel_chunks(count, threads, [&](std::size_t b, std::size_t e) {
    std::memcpy(out + b, in + b, (e - b) * sizeof(float));
  });
}

template <int N>
void run_order(std::size_t items, int runs, int threads) {
  constexpr std::size_t n = N * N, item = 3 * n;
  std::vector<float> in(items * item), out(items * item), planes(items * item);
  std::mt19937_64 rng(N);
  zhf::sh::Normal<float> normal;
  for (float& x : in) x = normal(rng);
  for (std::size_t v = 0; v < items; ++v)
    for (std::size_t c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < n; ++i)
        planes[(c * n + i) * items + v] = i == 0 ? in[item * v + c] : in[item * v + 3 + c * (n - 1) + i - 1];
  const double axis[3] = {0.48, 0.6, 0.64};
  const zhf::runtime::Matrix3 r = zhf::runtime::rotation_about_unit_axis(axis, 1.1);
  float rf[9];
  for (int i = 0; i < 9; ++i) rf[i] = float(r[i]);
  const auto dense = zhf::runtime::Rotator<float>::of<N>().dense(rf);
  const double bytes = 2.0 * items * item * sizeof(float);
  const double t_copy = best_seconds(runs, [&] { copy(in.data(), out.data(), in.size(), threads); });
  const double t_splats = best_seconds(runs, [&] { dense.apply_splats(items, in.data(), out.data(), threads); });
  const double t_planar = best_seconds(runs, [&] { dense.apply_planar(items, 3, planes.data(), out.data(), threads); });
  // In place (what a scene editor does): no write-allocate reads of the output.
  const double t_splats_in_place = best_seconds(runs, [&] { dense.apply_splats(items, in.data(), in.data(), threads); });
  const double t_planar_in_place = best_seconds(runs, [&] { dense.apply_planar(items, 3, planes.data(), planes.data(), threads); });
  auto report = [&](const char* name, double seconds, double in_place) {
    std::printf("; %s %.1f ns/item %.1f GB/s %.0f%% of copy, in place %.1f ns/item %.0f%%", name, seconds / items * 1e9,
                bytes / seconds / 1e9, 100 * t_copy / seconds, in_place / items * 1e9, 100 * t_copy / in_place);
  };
  std::printf("N=%d threads=%d items=%zu (%.0f MB moved): copy %.1f GB/s", N, threads, items, bytes / 1e6, bytes / t_copy / 1e9);
  report("splats", t_splats, t_splats_in_place);
  report("planar", t_planar, t_planar_in_place);
  std::printf("\n");
}

template <int N>
void run_soa(std::size_t count, std::size_t stride, int runs) {
  constexpr std::size_t n = N * N;
  std::vector<float> r(9 * stride), in(n * stride), out(n * stride);
  std::mt19937_64 rng(N);
  zhf::sh::Normal<> normal;
  for (std::size_t v = 0; v < count; ++v) {
    double axis[3] = {normal(rng), normal(rng), normal(rng)};
    const double length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    for (double& a : axis) a /= length;
    const zhf::runtime::Matrix3 m = zhf::runtime::rotation_about_unit_axis(axis, 3 * normal(rng));
    for (int k = 0; k < 9; ++k) r[k * stride + v] = float(m[k]);
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t v = 0; v < count; ++v) in[i * stride + v] = float(normal(rng));
  // The generated loop takes no stride: timed where the planes are count apart.
  char generated[32] = "-";
  if (stride == count) {
    const double t = best_seconds(
        runs * 5, [&] { zhf::gen::Kernels<N>::template rotate_batch<float>(count, r.data(), in.data(), out.data()); });
    std::snprintf(generated, sizeof generated, "%.2f ns", t / count * 1e9);
  }
  const double t_packs = best_seconds(runs * 5, [&] { zhf::runtime::rotate_soa<N>(count, stride, r.data(), in.data(), out.data()); });
  // The scalar kernel once per rotation, on the same rotations and vectors laid out one after
  // another in one buffer from a line (in three heap arrays its time moved by 6 % with where they
  // fell).
  constexpr std::size_t line = zhf::runtime::kCacheLineBytes / sizeof(float);
  std::vector<float> each(9 * count + 2 * n * count + line);
  float* const r_each = each.data() + (line - reinterpret_cast<std::uintptr_t>(each.data()) / sizeof(float) % line) % line;
  float* const in_each = r_each + 9 * count;
  float* const out_each = in_each + n * count;
  for (std::size_t v = 0; v < count; ++v) {
    for (int k = 0; k < 9; ++k) r_each[9 * v + k] = r[k * stride + v];
    for (std::size_t i = 0; i < n; ++i) in_each[n * v + i] = in[i * stride + v];
  }
  const double t_scalar = best_seconds(runs * 5, [&] {
    for (std::size_t v = 0; v < count; ++v)
      zhf::gen::Kernels<N>::template rotate<float>(&r_each[9 * v], &in_each[n * v], &out_each[n * v]);
  });
  std::printf("N=%d soa, %zu rotations, planes %zu apart, one thread: rotate_soa %.2f ns per rotation; generated rotate_batch %s; "
              "scalar rotate per rotation %.2f ns (%.2fx rotate_soa)\n",
              N, count, stride, t_packs / count * 1e9, generated, t_scalar / count * 1e9, t_scalar / t_packs);
}

}  // namespace

int main(int argc, char** argv) {
  const long items_arg = argc > 1 ? std::atol(argv[1]) : 1 << 20, runs = argc > 2 ? std::atol(argv[2]) : 7;
  if (items_arg < 1 || runs < 1 || items_arg > (1L << 26)) {
    std::fprintf(stderr, "zhf_bulk_bench: items must be 1..2^26 and runs >= 1\n");
    return 2;
  }
  const std::size_t items = std::size_t(items_arg);
  const int all = int(std::max(1u, std::thread::hardware_concurrency()));
  for (int threads : {1, all}) {
    run_order<4>(items, int(runs), threads);
    run_order<8>(items / 4, int(runs), threads);
  }
  // Planes 16 KiB apart (a power of two: rotate_soa copies the inputs through its block), the same
  // count on planes padded to soa_plane_stride, then a count that spreads them itself.
  const struct {
    std::size_t count, stride;
  } layouts[] = {{4096, 4096}, {4096, zhf::runtime::soa_plane_stride<3, float>(4096)}, {4000, 4000}};
  for (const auto& layout : layouts) {
    run_soa<3>(layout.count, layout.stride, int(runs));
    run_soa<4>(layout.count, layout.stride, int(runs));
    run_soa<5>(layout.count, layout.stride, int(runs));
    run_soa<6>(layout.count, layout.stride, int(runs));
    run_soa<7>(layout.count, layout.stride, int(runs));
    run_soa<8>(layout.count, layout.stride, int(runs));
  }
  return 0;
}
