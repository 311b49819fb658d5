// How far each instruction-set path of zhf::dispatch is from the arithmetic bound, in one run:
// for every path this CPU runs and orders 2..8, 16, 32, 64, 128, the time of one rotation (a new
// rotation per vector, Rotator<float>::rotate_batch on one thread, best of the repetitions)
// against the time the rotation's arithmetic would take with every lane of every vector
// instruction busy, two vector instructions per cycle:
//   orders 2..8   the generated kernel's counts (generated/manifest.json, rotate_orderN):
//                 max(multiplies, adds) instructions of `lanes` floats where the path has FMA,
//                 multiplies + adds where it has not;
//   orders 9..    zxzxz's (runtime/zxzxz_rotation.h): 2 sum_l h ceil(4h/lanes) pack
//                 multiply-adds (two instructions each without FMA) and 6 sum_l ceil(4h/lanes)
//                 pack operations for the turns, h = l/2 + 1, bands l = 1..N-1.
// Lanes: 4 floats for sse2 (no FMA), 8 for avx2, 16 for avx512, 4 for neon (FMA); the bound for
// avx512 assumes two 512-bit units (one on AMD Zen 4, which halves its rate). The clock is the
// one given (GHz), else /proc/cpuinfo's first "cpu MHz".
//   zhf_fma_bound_bench [--ghz 2.45] [--reps 31]
// Prints one Markdown table per path of the architecture, the bound alone for a path this CPU
// lacks. Emulated runs (qemu) time nothing meaningful.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "zhf/codegen/manifest.h"
#include "zhf/dispatch/rotator.h"
#include "zhf/sh/random.h"
#include "zhf/sh/rotation_matrix.h"

namespace {

using zhf::dispatch::Isa;

struct Width {
  int lanes;
  bool fma;
};

Width width_of(Isa isa) {
  switch (isa) {
    case Isa::kSse2: return {4, false};
    case Isa::kAvx2: return {8, true};
    case Isa::kAvx512: return {16, true};
    case Isa::kNeon: return {4, true};
    case Isa::kSimd128: return {4, false};  // relaxed-SIMD FMA is not in SIMD128
    case Isa::kGeneric: return {1, false};
  }
  return {1, false};
}

struct Counts {
  long multiplies = 0, adds = 0;
};

// rotate_orderN's counts from the manifest zhf generate writes.
Counts generated_counts(const zhf::codegen::Manifest& manifest, int order) {
  const std::string name = "rotate_order" + std::to_string(order);
  if (const zhf::codegen::ManifestFile* file = manifest.kernels(order, zhf::codegen::Language::kCpp))
    for (const zhf::codegen::EmittedFunction& f : file->functions)
      if (f.name == name) return {f.ops.multiplies, f.ops.adds};
  std::fprintf(stderr, "zhf_fma_bound_bench: generated/manifest.json has no %s\n", name.c_str());
  std::exit(1);
}

// Vector instructions of the bound for one rotation of the order.
double bound_instructions(const zhf::codegen::Manifest& manifest, int order, Width w) {
  if (order <= 8) {
    const Counts c = generated_counts(manifest, order);
    return double(w.fma ? std::max(c.multiplies, c.adds) : c.multiplies + c.adds) / w.lanes;
  }
  double products = 0, turns = 0;
  for (int l = 1; l < order; ++l) {
    const long h = l / 2 + 1, packs = (4 * h + w.lanes - 1) / w.lanes;
    products += 2.0 * h * packs;
    turns += 6.0 * packs;
  }
  return products * (w.fma ? 1 : 2) + turns;
}

double clock_ghz(int argc, char** argv) {
  for (int k = 1; k + 1 < argc; ++k)
    if (std::strcmp(argv[k], "--ghz") == 0) return std::atof(argv[k + 1]);
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);)
    if (line.rfind("cpu MHz", 0) == 0) return std::atof(line.substr(line.find(':') + 1).c_str()) / 1000;
  return 0;
}

int reps_of(int argc, char** argv) {
  for (int k = 1; k + 1 < argc; ++k)
    if (std::strcmp(argv[k], "--reps") == 0) return std::max(1, std::atoi(argv[k + 1]));
  return 31;
}

// ns per rotation: count vectors each with its own rotation, best of reps calls.
double time_rotation(int order, std::size_t count, int reps, std::mt19937_64& rng) {
  const auto rotator = zhf::dispatch::Rotator<float>::make(order);
  const std::size_t n = std::size_t(order) * order;
  std::vector<float> r(9 * count), in(n * count), out(n * count);
  zhf::sh::Normal<float> normal;
  for (std::size_t v = 0; v < count; ++v) {
    const zhf::sh::RotationMatrix m = zhf::sh::random_rotation(rng);
    for (int k = 0; k < 9; ++k) r[9 * v + k] = float(m(k / 3, k % 3));
  }
  for (float& x : in) x = normal(rng);
  double best = 1e30;
  for (int rep = 0; rep < reps; ++rep) {
    const auto start = std::chrono::steady_clock::now();
    rotator.rotate_batch(count, r.data(), in.data(), out.data(), 1);
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best / count * 1e9;
}

// ns as a table shows them: three significant digits, whole ns from 1000.
std::string ns(double value) {
  char text[32];
  std::snprintf(text, sizeof text, value < 1000 ? "%.3g" : "%.0f", value);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  const double ghz = clock_ghz(argc, argv);
  const int reps = reps_of(argc, argv);
  if (!(ghz > 0)) {
    std::fprintf(stderr, "zhf_fma_bound_bench: no clock rate: give --ghz\n");
    return 2;
  }
  const zhf::codegen::Manifest manifest = zhf::codegen::read_manifest(std::string(ZHF_SOURCE_DIR) + "/generated/manifest.json");
  std::printf("clock %.2f GHz, two vector instructions per cycle; best of %d calls of rotate_batch, one thread\n", ghz, reps);
  const std::vector<Isa> supported = zhf::dispatch::supported_isas();
#if defined(__x86_64__)
  const std::vector<Isa> paths = {Isa::kAvx512, Isa::kAvx2, Isa::kSse2};
#elif defined(__aarch64__)
  const std::vector<Isa> paths = {Isa::kNeon};
#else
  const std::vector<Isa> paths = {Isa::kGeneric};
#endif
  for (const Isa isa : paths) {
    const bool runs = std::find(supported.begin(), supported.end(), isa) != supported.end();
    const Width w = width_of(isa);
    std::printf("\n%s (%d float lanes, %s)%s\n\n", zhf::dispatch::isa_name(isa), w.lanes, w.fma ? "FMA" : "no FMA",
                runs ? "" : ": not measured, this CPU lacks it");
    if (runs) zhf::dispatch::use_isa(zhf::dispatch::isa_name(isa));
    std::printf("| order | path | bound: instructions | bound ns | measured ns | measured / bound |\n");
    std::printf("| --- | --- | --- | --- | --- | --- |\n");
    std::mt19937_64 rng(1);
    for (const int order : {2, 3, 4, 5, 6, 7, 8, 16, 32, 64, 128}) {
      const double instructions = bound_instructions(manifest, order, w);
      const double bound_ns = instructions / 2 / ghz;
      if (!runs) {
        std::printf("| %d | - | %.1f | %s | - | - |\n", order, instructions, ns(bound_ns).c_str());
        continue;
      }
      const std::size_t count = order <= 32 ? 1024 : order == 64 ? 128 : 16;
      const double measured = time_rotation(order, count, reps, rng);
      std::printf("| %d | %s | %.1f | %s | %s | %.1f |\n", order, zhf::dispatch::Rotator<float>::make(order).path().c_str(),
                  instructions, ns(bound_ns).c_str(), ns(measured).c_str(), measured / bound_ns);
    }
  }
  return 0;
}
