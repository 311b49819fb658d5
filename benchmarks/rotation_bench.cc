// ns per rotation, one vector with a new random rotation per call (float unless named).
//   zhf/N          generated kernel rotate_orderN<float>
//   zhf_rgb/N      generated RGB kernel, per call (three channels)
//   zhf_json/N     runtime rotator from the lobe table (loops)
//   ivanic/N       the project's Ivanic-Ruedenberg reference (double, Eigen), build + apply
//   dense_apply/N  apply precomputed band matrices (float), the floor for a shared rotation
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "zhf/runtime/rotator.h"
#include "zhf_kernels.h"
#include "zhf/runtime/table_io.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"

namespace {

constexpr int kPool = 1024;

struct Inputs {
  std::vector<float> r, f;
  std::vector<zhf::sh::RotationMatrix> rd;
  Inputs(int order) {
    std::mt19937_64 rng(7);
    zhf::sh::Normal<float> normal;
    for (int k = 0; k < kPool; ++k) {
      const zhf::sh::RotationMatrix m = zhf::sh::random_rotation(rng);
      rd.push_back(m);
      for (int i = 0; i < 9; ++i) r.push_back(static_cast<float>(m(i / 3, i % 3)));
      for (int i = 0; i < 3 * order * order; ++i) f.push_back(normal(rng));
    }
  }
};

void zhf_generated(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Inputs in(n);
  const auto rotator = zhf::runtime::Rotator<float>::with(zhf::gen::scalar_kernels<float>(n));
  std::vector<float> out(n * n);
  int k = 0;
  for (auto _ : state) {
    rotator.rotate(&in.r[9 * k], &in.f[3 * n * n * k], out.data());
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
    k = (k + 1) % kPool;
  }
}

void zhf_rgb(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Inputs in(n);
  const auto rotator = zhf::runtime::Rotator<float>::with(zhf::gen::scalar_kernels<float>(n));
  std::vector<float> out(3 * n * n);
  int k = 0;
  for (auto _ : state) {
    rotator.rotate_rgb(&in.r[9 * k], &in.f[3 * n * n * k], out.data());
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
    k = (k + 1) % kPool;
  }
}

void zhf_json(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Inputs in(n);
  const auto rotator = zhf::runtime::Rotator<float>::from_table(
      zhf::runtime::read_lobe_table(zhf::runtime::table_path(ZHF_SOURCE_DIR "/generated/lobes", n), n));
  std::vector<float> out(n * n);
  int k = 0;
  for (auto _ : state) {
    rotator.rotate(&in.r[9 * k], &in.f[3 * n * n * k], out.data());
    benchmark::DoNotOptimize(out.data());
    k = (k + 1) % kPool;
  }
}

void ivanic(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Inputs in(n);
  Eigen::VectorXd f = Eigen::VectorXd::Random(n * n);
  int k = 0;
  for (auto _ : state) {
    const Eigen::VectorXd g = zhf::sh::apply_band_matrices(zhf::sh::ivanic_ruedenberg(in.rd[k], n), f);
    benchmark::DoNotOptimize(g.data());
    k = (k + 1) % kPool;
  }
}

void dense_apply(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Inputs in(n);
  const auto rotator = zhf::runtime::Rotator<float>::with(zhf::gen::scalar_kernels<float>(n));
  std::vector<zhf::runtime::DenseRotation<float>> dense;
  for (int k = 0; k < 64; ++k) dense.push_back(rotator.dense(&in.r[9 * k]));
  std::vector<float> out(n * n);
  int k = 0;
  for (auto _ : state) {
    dense[k % 64].apply(&in.f[3 * n * n * k], out.data());
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
    k = (k + 1) % kPool;
  }
}

BENCHMARK(zhf_generated)->Name("zhf")->DenseRange(3, 8);
BENCHMARK(zhf_rgb)->Name("zhf_rgb")->DenseRange(3, 8);
BENCHMARK(zhf_json)->Name("zhf_json")->DenseRange(3, 8);
BENCHMARK(ivanic)->Name("ivanic")->DenseRange(3, 8);
BENCHMARK(dense_apply)->Name("dense_apply")->DenseRange(3, 8);

}  // namespace

BENCHMARK_MAIN();
