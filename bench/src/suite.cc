#include "zhf/bench/suite.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include "healpix_method.h"
#include "lanes_kernels.h"
#include "zhf/bench/limits.h"
#include "zhf/bench/machine.h"
#include "zhf/codegen/manifest.h"
#include "zhf/dispatch/rotator.h"
#include "zhf/frames/tight_frame_rotation.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/process.h"
#include "zhf/io/signals.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/parallel.h"
#include "zhf/runtime/table_io.h"
#include "zhf/runtime/product.h"
#include "zhf/runtime/rotator.h"
#include "zhf/runtime/soa_batch.h"
#include "zhf_kernels.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/zxzxz.h"

namespace zhf::bench {
namespace fs = std::filesystem;
namespace {

// The "pruned" rows drop the entries of A_l below these fractions of the band's largest.
constexpr double kPruneSmall = 1e-3, kPruneLarge = 1e-2;  // an input, not a tolerance


using Clock = std::chrono::steady_clock;

// Scale of one run.
struct Scale {
  int pool;           // distinct inputs per order (errors are measured on all of them)
  int repeats;        // timed repeats; median, min and max are reported
  double seconds;     // target time of one repeat
  size_t batch;       // vectors in the batch and shared scenarios
  int worst_rotations;  // rotations searched for the worst unit input (single vector)
};

// Random rotations and unit-norm coefficient vectors (three channels each), with the double
// reference rotation of every channel.
struct Pool {
  int order = 0, n = 0, size = 0;
  std::vector<sh::RotationMatrix> r;
  std::vector<double> rd, fd;   // 9 and 3 N^2 per input
  std::vector<float> rf, ff;
  std::vector<double> reference;  // 3 N^2 per input

  Pool(int order_, int count) : order(order_), n(order_ * order_), size(count) {
    std::mt19937_64 rng(1000 + order);
    sh::Normal<> normal;
    for (int k = 0; k < count; ++k) {
      r.push_back(sh::random_rotation(rng));
      for (int i = 0; i < 9; ++i) rd.push_back(r.back()(i / 3, i % 3));
      // The quadrature projection: independent of every method measured, Ivanic-Ruedenberg included.
      const sh::BandMatrices bands = sh::quadrature_rotation(r.back(), order);
      for (int c = 0; c < 3; ++c) {
        Eigen::VectorXd f(n);
        for (int i = 0; i < n; ++i) f[i] = normal(rng);
        f.normalize();
        fd.insert(fd.end(), f.data(), f.data() + n);
        const Eigen::VectorXd g = sh::apply_band_matrices(bands, f);
        reference.insert(reference.end(), g.data(), g.data() + n);
      }
    }
    rf.assign(rd.begin(), rd.end());
    ff.assign(fd.begin(), fd.end());
  }
  template <class T>
  const T* rot(int k) const {
    if constexpr (std::is_same_v<T, float>) return &rf[9 * size_t(k)];
    else return &rd[9 * size_t(k)];
  }
  template <class T>
  const T* coeffs(int k) const {
    if constexpr (std::is_same_v<T, float>) return &ff[3 * size_t(n) * k];
    else return &fd[3 * size_t(n) * k];
  }
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Times `call(k)` over the pool until a repeat lasts scale.seconds; ns per call.
template <class F>
void time_calls(const Scale& scale, int pool, F&& call, Row& row) {
  auto run = [&](long calls) {
    const auto t0 = Clock::now();
    for (long i = 0; i < calls; ++i) call(static_cast<int>(i % pool));
    return std::chrono::duration<double, std::nano>(Clock::now() - t0).count();
  };
  const double first = run(pool);  // warm-up and calibration
  const long calls = std::max<long>(pool, static_cast<long>(scale.seconds * 1e9 / std::max(1.0, first / pool)));
  std::vector<double> ns;
  for (int rep = 0; rep < scale.repeats; ++rep) ns.push_back(run(calls) / calls);
  row.ns_median = median(ns);
  row.ns_min = *std::min_element(ns.begin(), ns.end());
  row.ns_max = *std::max_element(ns.begin(), ns.end());
}

// Error of outputs out[k * stride + c * n + i] against the pool's reference, channels c.
template <class T>
void measure_error(const Pool& pool, const std::vector<T>& out, int channels, int count, Row& row) {
  double worst = 0, sum = 0;
  size_t terms = 0;
  for (int k = 0; k < count; ++k)
    for (int c = 0; c < channels; ++c)
      for (int i = 0; i < pool.n; ++i) {
        const double e = std::abs(double(out[(size_t(k) * channels + c) * pool.n + i]) - pool.reference[(3 * size_t(k) + c) * pool.n + i]);
        worst = std::isnan(e) ? INFINITY : std::max(worst, e);
        sum += e * e;
        ++terms;
      }
  row.max_error = worst;
  row.rms_error = std::sqrt(sum / std::max<size_t>(1, terms));
}

// The worst unit input of a linear method (sh::worst_unit_input_error), over the first
// `rotations` rotations of the pool against its quadrature reference.
template <class T, class F>
void measure_worst_unit_input(const Pool& pool, int rotations, F&& rotate, Row& row) {
  double worst = 0;
  for (int k = 0; k < std::min(rotations, pool.size); ++k) {
    const auto rotate_k = [&](const T* in, T* out) { rotate(pool.rot<T>(k), in, out); };
    worst = std::max(worst, sh::worst_unit_input_error<T>(sh::quadrature_rotation(pool.r[k], pool.order), rotate_k));
  }
  row.worst_unit_error = worst;
}

Row make_row(const std::string& method, const std::string& scenario, const std::string& precision, int order,
             const std::string& variant = "") {
  Row r;
  r.method = method;
  r.scenario = scenario;
  r.precision = precision;
  r.order = order;
  r.variant = variant;
  return r;
}

// One vector (channels = 1) or planar RGB (3) per call, a new rotation each time:
// rotate(R, in, out) on T.
template <class T, class F>
Row single(const Scale& scale, const Pool& pool, const std::string& method, const std::string& scenario, int channels,
           F&& rotate, const std::string& variant = "") {
  Row row = make_row(method, scenario, std::is_same_v<T, float> ? "float" : "double", pool.order, variant);
  std::vector<T> out(size_t(pool.size) * channels * pool.n);
  // Channel c of input k is the pool's channel c: the coefficients are contiguous per input.
  time_calls(scale, pool.size, [&](int k) { rotate(pool.rot<T>(k), pool.coeffs<T>(k), &out[size_t(k) * channels * pool.n]); }, row);
  measure_error(pool, out, channels, pool.size, row);
  if (channels == 1) measure_worst_unit_input<T>(pool, scale.worst_rotations, rotate, row);
  return row;
}

// Scenario "product": h = P_N(f g) of the pool's channels 0 and 1 (and f^2), against the double
// Gaunt loop of runtime/product.h. product(f, g, h) on T; g null: the square.
template <class T, class F>
Row product_row(const Scale& scale, const Pool& pool, const std::string& method, bool square, F&& product) {
  Row row = make_row(method, square ? "square" : "product", std::is_same_v<T, float> ? "float" : "double", pool.order);
  const runtime::ShProduct exact(pool.order);
  std::vector<T> out(size_t(pool.size) * pool.n);
  time_calls(scale, pool.size, [&](int k) {
    const T* f = pool.coeffs<T>(k);
    product(f, square ? f : f + pool.n, &out[size_t(k) * pool.n]);
  }, row);
  double worst = 0, sum = 0;
  std::vector<double> h(pool.n);
  for (int k = 0; k < pool.size; ++k) {
    const double* f = pool.coeffs<double>(k);
    exact.product(f, square ? f : f + pool.n, h.data());
    for (int i = 0; i < pool.n; ++i) {
      const double e = std::abs(double(out[size_t(k) * pool.n + i]) - h[i]);
      worst = std::isnan(e) ? INFINITY : std::max(worst, e);
      sum += e * e;
    }
  }
  row.max_error = worst;
  row.rms_error = std::sqrt(sum / (double(pool.size) * pool.n));
  return row;
}

// Scenario "shade": the pool's channel 0 rotated and integrated against channel 1, against the
// quadrature reference. shade(R, light, transfer) -> T.
template <class T, class F>
Row shade_row(const Scale& scale, const Pool& pool, const std::string& method, const std::string& variant, F&& shade) {
  Row row = make_row(method, "shade", std::is_same_v<T, float> ? "float" : "double", pool.order, variant);
  std::vector<T> out(pool.size);
  time_calls(scale, pool.size, [&](int k) { out[k] = shade(pool.rot<T>(k), k); }, row);
  double worst = 0, sum = 0;
  for (int k = 0; k < pool.size; ++k) {
    double expected = 0;
    for (int i = 0; i < pool.n; ++i) expected += pool.reference[3 * size_t(k) * pool.n + i] * pool.coeffs<double>(k)[pool.n + i];
    const double e = std::abs(double(out[k]) - expected);
    worst = std::isnan(e) ? INFINITY : std::max(worst, e);
    sum += e * e;
  }
  row.max_error = worst;
  row.rms_error = std::sqrt(sum / pool.size);
  return row;
}

// Operation counts through a counting scalar (zxzxz), as implemented.
struct Counted {
  double v = 0;
  static inline long multiplies = 0, adds = 0, calls = 0;
  Counted() = default;
  Counted(double x) : v(x) {}  // NOLINT: constants convert implicitly, as T(x) does
  friend Counted operator*(Counted a, Counted b) { return ++multiplies, Counted(a.v * b.v); }
  friend Counted operator+(Counted a, Counted b) { return ++adds, Counted(a.v + b.v); }
  friend Counted operator-(Counted a, Counted b) { return ++adds, Counted(a.v - b.v); }
  friend Counted operator-(Counted a) { return ++adds, Counted(-a.v); }
  friend bool operator>=(Counted a, Counted b) { return a.v >= b.v; }
  friend Counted atan2(Counted a, Counted b) { return ++calls, Counted(std::atan2(a.v, b.v)); }
  friend Counted hypot(Counted a, Counted b) { return ++calls, Counted(std::hypot(a.v, b.v)); }
  friend Counted sin(Counted a) { return ++calls, Counted(std::sin(a.v)); }
  friend Counted cos(Counted a) { return ++calls, Counted(std::cos(a.v)); }
};

void count_zxzxz(int order, Row& row) {
  const sh::ZxzxzRotator<Counted> z(order);
  const sh::RotationMatrix m = sh::rotation_from_zyz(0.3, 1.1, -0.4);
  std::vector<Counted> r(9), in(order * order), out(order * order);
  for (int i = 0; i < 9; ++i) r[i] = m(i / 3, i % 3);
  Counted::multiplies = Counted::adds = Counted::calls = 0;
  z.rotate(r.data(), in.data(), out.data());
  row.multiplies = Counted::multiplies;
  row.adds = Counted::adds;
}

// Op counts of the generated C++ kernels, from the manifest.
std::map<std::string, std::pair<long, long>> manifest_counts(const fs::path& manifest) {
  std::map<std::string, std::pair<long, long>> out;
  for (const codegen::ManifestFile& f : codegen::read_manifest(manifest.string()).files)
    if (f.language == codegen::Language::kCpp)
      for (const codegen::EmittedFunction& fn : f.functions) out[fn.name] = {fn.ops.multiplies, fn.ops.adds};
  return out;
}

// A table with every entry of A below threshold * max |A| set to zero (no longer the exact
// inverse of its lobes: Rotator::from_table checks its shape only).
runtime::LobeTable pruned(runtime::LobeTable table, double threshold) {
  for (runtime::TableBand& band : table.bands) {
    double largest = 0;
    for (double a : band.inverse.values) largest = std::max(largest, std::abs(a));
    for (double& a : band.inverse.values)
      if (std::abs(a) < threshold * largest) a = 0;
  }
  return table;
}

long nonzeros(const runtime::LobeTable& table) {
  long count = 0;
  for (const runtime::TableBand& band : table.bands)
    for (double a : band.inverse.values) count += a != 0;
  return count;
}

// count vectors, each its own rotation (taken round-robin from the pool), over threads.
template <class F>
Row batch(const Scale& scale, const Pool& pool, const std::string& method, int threads, F&& rotate_range,
          size_t count) {
  Row row = make_row(method, "batch", "float", pool.order, "threads " + std::to_string(threads));
  const size_t n = pool.n;
  std::vector<float> r(9 * count), in(n * count), out(n * count);
  for (size_t v = 0; v < count; ++v) {
    const int k = static_cast<int>(v % pool.size);
    std::copy(pool.rot<float>(k), pool.rot<float>(k) + 9, &r[9 * v]);
    std::copy(pool.coeffs<float>(k), pool.coeffs<float>(k) + n, &in[n * v]);
  }
  std::vector<double> ns;
  for (int rep = 0; rep < std::max(1, scale.repeats / 2); ++rep) {
    const auto t0 = Clock::now();
    const size_t chunk = (count + threads - 1) / threads;
    runtime::parallel_for(threads, threads, [&](int t) {
      rotate_range(std::min(count, t * chunk), std::min(count, (t + 1) * chunk), r.data(), in.data(), out.data());
    });
    ns.push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / count);
  }
  row.ns_median = median(ns);
  row.ns_min = *std::min_element(ns.begin(), ns.end());
  row.ns_max = *std::max_element(ns.begin(), ns.end());
  // Errors on the first pool entries (input v is pool entry v % pool, channel 0).
  std::vector<float> first(size_t(pool.size) * n);
  std::copy(out.begin(), out.begin() + std::min(out.size(), first.size()), first.begin());
  measure_error(pool, first, 1, static_cast<int>(std::min<size_t>(pool.size, count)), row);
  return row;
}

// The same over structure-of-arrays slices, one per thread: element i of vector v of a
// slice of m vectors at [i * m + v].
template <class F>
Row batch_soa(const Scale& scale, const Pool& pool, const std::string& method, int threads, size_t count, F&& kernel) {
  Row row = make_row(method, "batch", "float", pool.order, "threads " + std::to_string(threads));
  const size_t n = pool.n, chunk = (count + threads - 1) / threads;
  struct Slice {
    size_t m;
    std::vector<float> r, in, out;
  };
  std::vector<Slice> slices;
  for (int t = 0; t < threads; ++t) {
    Slice s;
    s.m = std::min(count, (t + 1) * chunk) - std::min(count, t * chunk);
    s.r.resize(9 * s.m), s.in.resize(n * s.m), s.out.resize(n * s.m);
    for (size_t v = 0; v < s.m; ++v) {
      const int k = static_cast<int>((t * chunk + v) % pool.size);
      for (int i = 0; i < 9; ++i) s.r[i * s.m + v] = pool.rot<float>(k)[i];
      for (size_t i = 0; i < n; ++i) s.in[i * s.m + v] = pool.coeffs<float>(k)[i];
    }
    slices.push_back(std::move(s));
  }
  std::vector<double> ns;
  for (int rep = 0; rep < std::max(1, scale.repeats / 2); ++rep) {
    const auto t0 = Clock::now();
    runtime::parallel_for(threads, threads, [&](int t) {
      kernel(slices[t].m, slices[t].r.data(), slices[t].in.data(), slices[t].out.data());
    });
    ns.push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / count);
  }
  row.ns_median = median(ns);
  row.ns_min = *std::min_element(ns.begin(), ns.end());
  row.ns_max = *std::max_element(ns.begin(), ns.end());
  const int checked = static_cast<int>(std::min<size_t>(pool.size, slices[0].m));
  std::vector<float> first(size_t(checked) * n);
  for (int v = 0; v < checked; ++v)
    for (size_t i = 0; i < n; ++i) first[v * n + i] = slices[0].out[i * slices[0].m + v];
  measure_error(pool, first, 1, checked, row);
  return row;
}

}  // namespace

SuiteReport run_suite(const SuiteOptions& o) {
  const Scale scale = o.quick ? Scale{128, 3, 0.01, 1 << 15, 8} : Scale{512, 7, 0.05, 1 << 20, 64};
  std::vector<int> orders = o.orders;
  if (orders.empty()) orders = {2, 3, 4, 5, 6, 7, 8, 10, 12, 16};
  const fs::path root = o.source_dir;
  const auto counts = manifest_counts(root / "generated" / "manifest.json");
  SuiteReport report;
  report.cpu = cpu_model();
#ifdef __clang__
  report.compiler = std::string("clang ") + __clang_version__;
#else
  report.compiler = std::string("g++ ") + __VERSION__;
#endif
  report.flags = ZHF_BENCH_FLAGS;
  if (!lanes_arch().empty()) report.flags += "; zhf_lanes: -march=" + lanes_arch();
  report.date = today();
  auto say = [&](const Row& r) {
    io::throw_if_interrupted();
    report.rows.push_back(r);
    if (o.progress) {
      char line[200];
      std::snprintf(line, sizeof line, "N=%-2d %-7s %-22s %-16s %9.1f ns  max err %.2e", r.order, r.scenario.c_str(),
                    r.method.c_str(), r.variant.c_str(), r.ns_median, r.max_error);
      o.progress(line);
    }
  };
  auto with_counts = [&](Row r, const std::string& function) {
    const auto it = counts.find(function);
    if (it != counts.end()) r.multiplies = it->second.first, r.adds = it->second.second;
    return r;
  };

  for (int order : orders) {
    const Pool pool(order, scale.pool);
    const std::string on = "_order" + std::to_string(order);
    const bool generated = order >= 2 && order <= runtime::kMaxGeneratedOrder;
    const fs::path table_path = runtime::table_path((root / "generated" / "lobes").string(), order);
    const bool have_table = order >= 3 && fs::exists(table_path) && order <= bench::kMaxBenchOrder;

    // Scenario 1: one vector, a new rotation per call.
    if (generated) {
      const auto f = runtime::Rotator<float>::with(gen::scalar_kernels<float>(order));
      const auto d = runtime::Rotator<double>::with(gen::scalar_kernels<double>(order));
      say(with_counts(single<float>(scale, pool, "zhf", "single", 1, [&](auto r, auto in, auto out) { f.rotate(r, in, out); }), "rotate" + on));
      say(with_counts(single<double>(scale, pool, "zhf", "single", 1, [&](auto r, auto in, auto out) { d.rotate(r, in, out); }), "rotate" + on));
      const auto tailored = gen::with_order(order, [](auto n) -> void (*)(const float*, const float*, float*) {
        return &gen::Kernels<decltype(n)::value>::template rotate_signal_tailored<float>;
      });
      say(with_counts(single<float>(scale, pool, "zhf_signal_tailored", "single", 1, tailored), "rotate_signal_tailored" + on));
      say(with_counts(single<float>(scale, pool, "zhf", "rgb", 3, [&](auto r, auto in, auto out) { f.rotate_rgb(r, in, out); }), "rotate_rgb" + on));
      if (const FloatKernel lanes = lanes_kernel(order, false)) {
        say(single<float>(scale, pool, "zhf_lanes", "single", 1, [&](auto r, auto in, auto out) { lanes(r, in, out); }));
        // Knob: every step in float where the default widens some (faster, error past the model).
        if (lanes_stage(order) > 0) {
          const FloatKernel fast = lanes_kernel(order, true);
          say(single<float>(scale, pool, "zhf_lanes", "single", 1, [&](auto r, auto in, auto out) { fast(r, in, out); },
                            kAllFloatVariant));
        }
      }
    }
    // zhf as the CLI and the Python module run it: zhf::dispatch on the path it picks for this CPU
    // (the variant names the instruction set and the kernels).
    const auto shipped = dispatch::Rotator<float>::make(order);
    const std::string shipped_path = std::string(dispatch::isa_name(shipped.isa())) + ": " + shipped.path();
    say(single<float>(scale, pool, "zhf_dispatch", "single", 1, [&](auto r, auto in, auto out) { shipped.rotate(r, in, out); }, shipped_path));
    say(single<float>(scale, pool, "zhf_dispatch", "rgb", 3, [&](auto r, auto in, auto out) { shipped.rotate_rgb(r, in, out); }, shipped_path));
    if (have_table) {
      const runtime::LobeTable table = runtime::read_lobe_table(table_path.string(), order);
      const auto t = runtime::Rotator<float>::from_table(table);
      say(single<float>(scale, pool, "zhf_runtime", "single", 1, [&](auto r, auto in, auto out) { t.rotate(r, in, out); }));
      say(single<float>(scale, pool, "zhf_runtime", "rgb", 3, [&](auto r, auto in, auto out) { t.rotate_rgb(r, in, out); }));
      if (generated) {
        // Knob: pruned tables, through the runtime path (which skips A's zeros).
        for (double threshold : {kPruneSmall, kPruneLarge}) {
          const runtime::LobeTable p = pruned(table, threshold);
          const auto pr = runtime::Rotator<float>::from_table(p);
          char variant[96];
          std::snprintf(variant, sizeof variant, "pruned %.0e (%ld of %ld nonzeros)", threshold, nonzeros(p), nonzeros(table));
          say(single<float>(scale, pool, "zhf_runtime", "single", 1, [&](auto r, auto in, auto out) { pr.rotate(r, in, out); }, variant));
        }
      }
    }
    // Knobs: lobe sets from other searches (bench/tables): condition bound, no sharing.
    for (const auto& [file, variant] : std::vector<std::pair<std::string, std::string>>{
             {"order_6_cond50.json", "table cond<=50"}, {"order_5_no_sharing.json", "no sharing"},
             {"order_4_no_sharing.json", "no sharing"}}) {
      const fs::path path = root / "bench" / "tables" / file;
      if (!fs::exists(path)) continue;
      const runtime::LobeTable table = runtime::read_lobe_table(path.string());
      if (table.order != order) continue;
      const auto t = runtime::Rotator<float>::from_table(table);
      say(single<float>(scale, pool, "zhf_runtime", "single", 1, [&](auto r, auto in, auto out) { t.rotate(r, in, out); }, variant));
    }
    {
      const sh::ZxzxzRotator<float> z(order);
      Row row = single<float>(scale, pool, "zxzxz", "single", 1, [&](auto r, auto in, auto out) { z.rotate(r, in, out); });
      count_zxzxz(order, row);
      say(row);
      say(single<float>(scale, pool, "zxzxz", "rgb", 3, [&](auto r, auto in, auto out) { z.rotate_channels(r, in, out, 3); }));
    }
    if (order <= bench::kMaxBenchOrder) {
      // Lobes at a design's points: a tight frame, no inverse, condition 1 at every order.
      const frames::Cubature nodes = frames::design_cubature((root / "generated" / "designs").string(), 2 * (order - 1));
      const frames::TightFrameRotator<float> tight(order, nodes);
      say(single<float>(scale, pool, "tight_frame", "single", 1, [&](auto r, auto in, auto out) { tight.rotate(r, in, out); },
                        nodes.name + ", " + std::to_string(tight.lobes()) + " lobes"));
    }
    {
      // The usual general method: band matrices per rotation (double, Eigen), then applied.
      auto ir = [&](const double* r, const double* in, double* out, int channels) {
        const sh::BandMatrices bands = sh::ivanic_ruedenberg(Eigen::Map<const sh::RotationMatrix>(r), order);
        for (int c = 0; c < channels; ++c) {
          const Eigen::Map<const Eigen::VectorXd> f(in + c * pool.n, pool.n);
          Eigen::Map<Eigen::VectorXd>(out + c * pool.n, pool.n) = sh::apply_band_matrices(bands, f);
        }
      };
      say(single<double>(scale, pool, "ivanic_ruedenberg", "single", 1, [&](auto r, auto in, auto out) { ir(r, in, out, 1); }));
      say(single<double>(scale, pool, "ivanic_ruedenberg", "rgb", 3, [&](auto r, auto in, auto out) { ir(r, in, out, 3); }));
    }
    {
      const HealpixRotator h(order);
      say(single<double>(scale, pool, "healpix", "single", 1, [&](auto r, auto in, auto out) { h.rotate(r, in, out); }, "incl. real<->complex"));
      // The conversions' share of that time, alone (no rotation, so no error to report).
      Row convert = single<double>(scale, pool, "healpix", "single", 1, [&](auto r, auto in, auto out) { h.convert_only(r, in, out); }, "conversion only");
      convert.max_error = convert.rms_error = convert.worst_unit_error = NAN;
      say(convert);
    }

    if (!generated) continue;
    // Products and squares: the emitted kernels and the sparse Gaunt loop they replace.
    gen::with_order(order, [&](auto n_) {
      constexpr int N = decltype(n_)::value;
      using K = gen::Kernels<N>;
      const runtime::ShProduct sparse(N);
      for (bool square : {false, true}) {
        const std::string function = (square ? "square" : "product") + on;
        auto kernel_float = [&](const float* a, const float* b, float* h) {
          square ? K::template square<float>(a, h) : K::template product<float>(a, b, h);
        };
        auto kernel_double = [&](const double* a, const double* b, double* h) {
          square ? K::template square<double>(a, h) : K::template product<double>(a, b, h);
        };
        say(with_counts(product_row<float>(scale, pool, "zhf", square, kernel_float), function));
        say(with_counts(product_row<double>(scale, pool, "zhf", square, kernel_double), function));
        say(product_row<float>(scale, pool, "gaunt_sparse", square, [&](auto a, auto b, auto h) { sparse.product(a, b, h); }));
      }
      // Shading: one function, the two steps it fuses, and from lobe weights computed beforehand.
      auto transfer = [&](int k) { return pool.coeffs<float>(k) + pool.n; };
      say(with_counts(shade_row<float>(scale, pool, "zhf_shade", "", [&](const float* r, int k) {
        float result[1];
        K::template shade<float>(r, pool.coeffs<float>(k), transfer(k), result);
        return result[0];
      }), "shade" + on));
      say(shade_row<float>(scale, pool, "zhf_rotate_then_dot", "", [&](const float* r, int k) {
        float rotated[N * N];
        K::template rotate<float>(r, pool.coeffs<float>(k), rotated);
        float sum = 0;
        for (int i = 0; i < N * N; ++i) sum += rotated[i] * transfer(k)[i];
        return sum;
      }));
      if constexpr (N > 2) {
        std::vector<float> lobes(size_t(pool.size) * N * N);
        for (int k = 0; k < pool.size; ++k) K::template lobe_weights<float>(pool.coeffs<float>(k), &lobes[size_t(k) * N * N]);
        say(with_counts(shade_row<float>(scale, pool, "zhf_shade_lobes", "lobe weights precomputed", [&](const float* r, int k) {
          float result[1];
          K::template shade_lobes<float>(r, &lobes[size_t(k) * N * N], transfer(k), result);
          return result[0];
        }), "shade_lobes" + on));
      }
    });

    // Scenarios 3 and 4 at the generated orders.
    const size_t count = scale.batch;
    const auto f = runtime::Rotator<float>::with(gen::scalar_kernels<float>(order));
    const sh::ZxzxzRotator<float> z(order);
    const auto soa_kernel = gen::with_order(order, [](auto n) -> void (*)(std::size_t, const float*, const float*, float*) {
      return &gen::Kernels<decltype(n)::value>::template rotate_batch<float>;
    });
    using SoaKernel = void (*)(std::size_t, const float*, const float*, float*);
    const SoaKernel soa_packs = gen::with_order(order, [](auto n) -> SoaKernel {
      constexpr int N = decltype(n)::value;
      if constexpr (gen::Kernels<N>::kLobeStage == 0) {
        return [](std::size_t c, const float* r, const float* in, float* out) { runtime::rotate_soa<N>(c, r, in, out, 1); };
      } else {
        return nullptr;
      }
    });
    const size_t n = pool.n;
    for (int threads : {1, 2}) {
      say(batch(scale, pool, "zhf", threads, [&](size_t b, size_t e, const float* r, const float* in, float* out) {
        f.rotate_batch(e - b, r + 9 * b, in + n * b, out + n * b, 1);
      }, count));
      // The generated structure-of-arrays kernel, each thread on its own SoA slice (laid out
      // before timing, as a caller keeping SoA data would), and the same kernel across SIMD
      // lanes through runtime::rotate_soa where its lobe stage is float.
      say(batch_soa(scale, pool, "zhf_batch_soa", threads, count, soa_kernel));
      if (soa_packs) say(batch_soa(scale, pool, "zhf_rotate_soa", threads, count, soa_packs));
      say(batch(scale, pool, "zhf_dispatch", threads, [&](size_t b, size_t e, const float* r, const float* in, float* out) {
        shipped.rotate_batch(e - b, r + 9 * b, in + n * b, out + n * b, 1);
      }, count));
      say(batch(scale, pool, "zxzxz", threads, [&](size_t b, size_t e, const float* r, const float* in, float* out) {
        for (size_t v = b; v < e; ++v) z.rotate(r + 9 * v, in + n * v, out + n * v);
      }, count));
    }
    {
      // Scenario 4: one rotation for every vector. Dense band matrices built once (through
      // the zhf kernel), then a small product per vector; zhf per vector for comparison.
      Row dense_row = make_row("dense_apply", "shared", "float", order, "build once");
      Row planar_row = make_row("dense_planar", "shared", "float", order, "build once, planar");
      Row zhf_row = make_row("zhf", "shared", "float", order, "per vector");
      std::vector<float> in(n * count), out(n * count);
      for (size_t v = 0; v < count; ++v)
        std::copy(pool.coeffs<float>(0), pool.coeffs<float>(0) + n, &in[n * v]);
      // The planar layout: plane i holds coefficient i of every vector.
      std::vector<float> planes(n * count), planes_out(n * count);
      for (size_t v = 0; v < count; ++v)
        for (size_t i = 0; i < n; ++i) planes[i * count + v] = in[n * v + i];
      std::vector<double> dense_ns, planar_ns, zhf_ns;
      for (int rep = 0; rep < std::max(1, scale.repeats / 2); ++rep) {
        auto t0 = Clock::now();
        const runtime::DenseRotation<float> dense = f.dense(pool.rot<float>(0));
        for (size_t v = 0; v < count; ++v) dense.apply(&in[n * v], &out[n * v]);
        dense_ns.push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / count);
        t0 = Clock::now();
        f.dense(pool.rot<float>(0)).apply_planar(count, 1, planes.data(), planes_out.data(), 1);
        planar_ns.push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / count);
        t0 = Clock::now();
        for (size_t v = 0; v < count; ++v) f.rotate(pool.rot<float>(0), &in[n * v], &out[n * v]);
        zhf_ns.push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / count);
      }
      const runtime::DenseRotation<float> dense = f.dense(pool.rot<float>(0));
      std::vector<float> one(n);
      dense.apply(pool.coeffs<float>(0), one.data());
      measure_error(pool, one, 1, 1, dense_row);
      for (size_t i = 0; i < n; ++i) one[i] = planes_out[i * count];
      measure_error(pool, one, 1, 1, planar_row);
      f.rotate(pool.rot<float>(0), pool.coeffs<float>(0), one.data());
      measure_error(pool, one, 1, 1, zhf_row);
      for (auto [row, ns] : {std::pair<Row*, std::vector<double>*>{&dense_row, &dense_ns}, {&planar_row, &planar_ns}, {&zhf_row, &zhf_ns}}) {
        row->ns_median = median(*ns);
        row->ns_min = *std::min_element(ns->begin(), ns->end());
        row->ns_max = *std::max_element(ns->begin(), ns->end());
        say(*row);
      }
    }
  }
  return report;
}

}  // namespace zhf::bench
