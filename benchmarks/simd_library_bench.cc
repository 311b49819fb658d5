// Portable SIMD libraries against zhf's own vector code, on the same work, in one run: the
// measurement behind docs/design.md's choice of how the kernels reach several instruction sets.
//   kernels  the generated order-N rotate kernel, one step of 8 float rotations across the lanes
//            (rotate_soa's way; simd_library_steps.h), with four number types: zhf's Pack (GCC
//            vector extensions, this unit built with -march=x86-64-v3), xsimd::batch<float, avx2>,
//            Highway's 8-lane vector (its static AVX2 target), and Pack under a per-function
//            target("avx2,fma") attribute in a unit built without -march. Orders 2..8; the
//            shipped rotate_soa on the same data for reference.
//   bands01  bands 0 and 1 of one vector (order 2's whole rotation, 4 floats): the hand-written
//            AVX2 intrinsics (avx2_fma.h's rotate_bands01) against the same steps in Highway
//            and in xsimd, each called through a function pointer as Rotator calls it.
// Each variant is checked against the first (max |difference| printed) and timed as the best of
// `runs`, the variants interleaved within each run so that they share the machine's state, all of
// them writing the same output buffer.
// Built by bench/CMakeLists.txt where Debian's libhwy-dev and libxsimd-dev are installed:
//   bash benchmarks/simd_libraries.sh        (installs them, builds, runs; output as in
//                                        benchmarks/results/simd_libraries.txt)
//   zhf_simd_library_bench [runs=21]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <random>
#include <vector>

#include <hwy/highway.h>
#include <xsimd/xsimd.hpp>

#include "simd_library_steps.h"
#include "zhf/runtime/avx2_fma.h"
#include "zhf/runtime/soa_batch.h"
#include "zhf/sh/random.h"
#include "zhf/sh/rotation_matrix.h"

#if !ZHF_RUNTIME_AVX2_FMA || HWY_TARGET != HWY_AVX2
#error "simd_library_bench compares AVX2 code: build it with -march=x86-64-v3"
#endif

// simd_library_target_attribute.cc.
void rotate_steps_target_attribute(int order, std::size_t count, std::size_t stride, const float* R, const float* in,
                                   float* out);

namespace hn = hwy::HWY_NAMESPACE;

// The number types have external linkage, as zhf's Pack has: the kernels instantiated for a type
// local to this unit would be inlined into their one caller, and Pack's (a template every unit may
// instantiate) would not, which measures the linkage and not the type.
namespace zhf::bench {

// xsimd's 8-float AVX2 batch as a kernel number type.
struct XsimdLanes {
  using Batch = xsimd::batch<float, xsimd::avx2>;
  static constexpr int kLanes = int(Batch::size);
  Batch v;
  XsimdLanes() = default;
  XsimdLanes(double c) : v(float(c)) {}  // NOLINT: broadcast, as a scalar literal would be
  explicit XsimdLanes(Batch b) : v(b) {}
  static XsimdLanes load(const float* p) { return XsimdLanes(Batch::load_unaligned(p)); }
  void store(float* p) const { v.store_unaligned(p); }
  friend XsimdLanes operator+(XsimdLanes a, XsimdLanes b) { return XsimdLanes(a.v + b.v); }
  friend XsimdLanes operator-(XsimdLanes a, XsimdLanes b) { return XsimdLanes(a.v - b.v); }
  friend XsimdLanes operator*(XsimdLanes a, XsimdLanes b) { return XsimdLanes(a.v * b.v); }
  friend XsimdLanes operator-(XsimdLanes a) { return XsimdLanes(-a.v); }
  friend XsimdLanes select_positive(XsimdLanes x, XsimdLanes if_positive, XsimdLanes otherwise) {
    return XsimdLanes(xsimd::select(x.v > Batch(0.0f), if_positive.v, otherwise.v));
  }
  friend XsimdLanes reciprocal_sqrt(XsimdLanes x) { return XsimdLanes(Batch(1.0f) / xsimd::sqrt(x.v)); }
};

// Highway's 8-float vector (static dispatch: this unit's AVX2 target) as a kernel number type.
struct HighwayLanes {
  using D = hn::FixedTag<float, 8>;
  using Vec = hn::Vec<D>;
  static constexpr int kLanes = 8;
  Vec v;
  HighwayLanes() = default;
  HighwayLanes(double c) : v(hn::Set(D(), float(c))) {}  // NOLINT: broadcast
  explicit HighwayLanes(Vec x) : v(x) {}
  static HighwayLanes load(const float* p) { return HighwayLanes(hn::LoadU(D(), p)); }
  void store(float* p) const { hn::StoreU(v, D(), p); }
  friend HighwayLanes operator+(HighwayLanes a, HighwayLanes b) { return HighwayLanes(a.v + b.v); }
  friend HighwayLanes operator-(HighwayLanes a, HighwayLanes b) { return HighwayLanes(a.v - b.v); }
  friend HighwayLanes operator*(HighwayLanes a, HighwayLanes b) { return HighwayLanes(a.v * b.v); }
  friend HighwayLanes operator-(HighwayLanes a) { return HighwayLanes(hn::Neg(a.v)); }
  friend HighwayLanes select_positive(HighwayLanes x, HighwayLanes if_positive, HighwayLanes otherwise) {
    return HighwayLanes(hn::IfThenElse(x.v > hn::Zero(D()), if_positive.v, otherwise.v));
  }
  friend HighwayLanes reciprocal_sqrt(HighwayLanes x) { return HighwayLanes(hn::Set(D(), 1.0f) / hn::Sqrt(x.v)); }
};

}  // namespace zhf::bench

namespace {

using zhf::bench::HighwayLanes;
using zhf::bench::XsimdLanes;

// rotate_bands01's steps (avx2_fma.h) in Highway: rows 1..3 of R's columns by lane permutes of one
// 8-float load, R_22 put in lane 2, one multiply and two fused multiply-adds, in[0] in lane 0.
void bands01_highway(const float r[9], const float in[4], float out[4]) {
  const hn::FixedTag<float, 8> d8;
  const hn::FixedTag<float, 4> d4;
  const auto first8 = hn::LoadU(d8, r);
  auto column = [&](int j) {
    alignas(32) const int32_t lanes[8] = {0, 3 + j, (6 + j) % 8, j, 0, 0, 0, 0};
    return hn::LowerHalf(d4, hn::TableLookupLanes(first8, hn::SetTableIndices(d8, lanes)));
  };
  const auto lane2 = hn::AndNot(hn::FirstN(d4, 2), hn::FirstN(d4, 3));
  const auto column2 = hn::IfThenElse(lane2, hn::Set(d4, r[8]), column(2));
  auto sum = hn::Mul(column(1), hn::Set(d4, in[1]));
  sum = hn::MulAdd(column2, hn::Set(d4, in[2]), sum);
  sum = hn::MulAdd(column(0), hn::Set(d4, in[3]), sum);
  hn::StoreU(hn::IfThenElse(hn::FirstN(d4, 1), hn::Set(d4, in[0]), sum), d4, out);
}

// The same steps in xsimd: its batches are whole registers, so the three rows are 8 lanes wide
// (lanes 4..7 unused) and the 4 results leave through an 8-float store to a local.
void bands01_xsimd(const float r[9], const float in[4], float out[4]) {
  using B = xsimd::batch<float, xsimd::avx2>;
  using U = xsimd::batch<uint32_t, xsimd::avx2>;
  const B first8 = B::load_unaligned(r);
  const B column0 = xsimd::swizzle(first8, xsimd::batch_constant<U, 0, 3, 6, 0, 0, 0, 0, 0>());
  const B column1 = xsimd::swizzle(first8, xsimd::batch_constant<U, 0, 4, 7, 1, 0, 0, 0, 0>());
  const B column2 = xsimd::select(xsimd::batch_bool_constant<B, false, false, true, false, false, false, false, false>(),
                                  B(r[8]), xsimd::swizzle(first8, xsimd::batch_constant<U, 0, 5, 0, 2, 0, 0, 0, 0>()));
  B sum = column1 * B(in[1]);
  sum = xsimd::fma(column2, B(in[2]), sum);
  sum = xsimd::fma(column0, B(in[3]), sum);
  const B result = xsimd::select(xsimd::batch_bool_constant<B, true, false, false, false, false, false, false, false>(),
                                 B(in[0]), sum);
  alignas(32) float lanes[8];
  result.store_aligned(lanes);
  std::memcpy(out, lanes, 4 * sizeof(float));
}

using Clock = std::chrono::steady_clock;

double seconds_of(const std::function<void()>& work) {
  const auto start = Clock::now();
  work();
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Variant {
  const char* name;
  std::function<void()> work;  // writes the shared output
  double best = 1e30;
};

// Runs the variants interleaved `runs` times; prints each one's best per item and its ratio to the
// first, and its output's largest difference from the first's. They all write one output buffer:
// with a buffer each, the distance between a variant's loads and stores modulo 4 KiB (which the
// CPU's store forwarding checks first) differed, and order 2 moved by up to 1.6x with it.
void time_variants(const char* title, std::vector<Variant>& variants, int runs, double items, std::vector<float>& out) {
  for (int run = 0; run < runs; ++run)
    for (Variant& v : variants) v.best = std::min(v.best, seconds_of(v.work));
  std::printf("%s\n", title);
  std::vector<float> first;
  for (const Variant& v : variants) {
    std::fill(out.begin(), out.end(), 0.0f);
    v.work();
    if (first.empty()) first = out;
    double difference = 0;
    for (std::size_t i = 0; i < out.size(); ++i) difference = std::max(difference, double(std::fabs(out[i] - first[i])));
    std::printf("  %-22s %8.2f ns  %5.2fx  max |difference| %.1e\n", v.name, v.best / items * 1e9,
                v.best / variants.front().best, difference);
  }
}

std::vector<float> random_rotations(std::size_t count, std::size_t stride, std::mt19937_64& rng) {
  std::vector<float> planes(9 * stride);
  for (std::size_t v = 0; v < count; ++v) {
    const zhf::sh::RotationMatrix m = zhf::sh::random_rotation(rng);
    for (int k = 0; k < 9; ++k) planes[k * stride + v] = float(m(k / 3, k % 3));
  }
  return planes;
}

template <int N>
void run_kernels(int runs) {
  // 4000 rotations (planes not a power of two apart), a multiple of 8: no tail.
  constexpr std::size_t count = 4000, n = N * N;
  std::mt19937_64 rng(N);
  const std::vector<float> r = random_rotations(count, count, rng);
  std::vector<float> in(n * count);
  zhf::sh::Normal<float> normal;
  for (float& x : in) x = normal(rng);
  std::vector<float> out(n * count);
  float* const o = out.data();
  std::vector<Variant> variants = {
      {"zhf Pack (GCC vectors)",
       [&] { zhf::bench::rotate_steps<N, zhf::runtime::Pack<float>>(count, count, r.data(), in.data(), o); }},
      {"xsimd batch", [&] { zhf::bench::rotate_steps<N, XsimdLanes>(count, count, r.data(), in.data(), o); }},
      {"Highway Vec", [&] { zhf::bench::rotate_steps<N, HighwayLanes>(count, count, r.data(), in.data(), o); }},
      {"Pack, target attribute", [&] { rotate_steps_target_attribute(N, count, count, r.data(), in.data(), o); }},
      {"rotate_soa (shipped)", [&] { zhf::runtime::rotate_soa<N>(count, count, r.data(), in.data(), o); }},
  };
  char title[96];
  std::snprintf(title, sizeof title, "kernels N=%d: per rotation, %zu rotations, 8 per step", N, count);
  time_variants(title, variants, runs, double(count), out);
}

void run_bands01(int runs) {
  constexpr std::size_t count = 1024;
  std::mt19937_64 rng(2);
  std::vector<float> r(9 * count), in(4 * count);
  for (std::size_t v = 0; v < count; ++v) {
    const zhf::sh::RotationMatrix m = zhf::sh::random_rotation(rng);
    for (int k = 0; k < 9; ++k) r[9 * v + k] = float(m(k / 3, k % 3));
  }
  zhf::sh::Normal<float> normal;
  for (float& x : in) x = normal(rng);
  using Bands01 = void (*)(const float*, const float*, float*);
  // Through a pointer the compiler cannot see through, as Rotator calls a kernel.
  volatile Bands01 intrinsics = &zhf::runtime::avx2::rotate_bands01, highway = &bands01_highway, xs = &bands01_xsimd;
  std::vector<float> out(4 * count);
  auto over_all = [&](Bands01 f) {
    return [&, f] {
      for (std::size_t v = 0; v < count; ++v) f(&r[9 * v], &in[4 * v], &out[4 * v]);
    };
  };
  std::vector<Variant> variants = {
      {"AVX2 intrinsics", over_all(intrinsics)},
      {"Highway", over_all(highway)},
      {"xsimd", over_all(xs)},
  };
  time_variants("bands01 (order 2, one vector per call): per call", variants, runs * 20, double(count), out);
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::atoi(argv[1]) : 21;
  if (runs < 1 || argc > 2) {
    std::fprintf(stderr, "zhf_simd_library_bench: usage: zhf_simd_library_bench [runs >= 1]\n");
    return 2;
  }
  std::printf("Highway %d.%d.%d (static target %s), xsimd %d.%d.%d\n", HWY_MAJOR, HWY_MINOR, HWY_PATCH,
              hwy::TargetName(HWY_STATIC_TARGET), XSIMD_VERSION_MAJOR, XSIMD_VERSION_MINOR, XSIMD_VERSION_PATCH);
  run_kernels<2>(runs);
  run_kernels<3>(runs);
  run_kernels<4>(runs);
  run_kernels<5>(runs);
  run_kernels<6>(runs);
  run_kernels<7>(runs);
  run_kernels<8>(runs);
  run_bands01(runs);
  return 0;
}
