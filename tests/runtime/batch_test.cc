// The batch entry points (shared rotations and the bulk layouts on every zhf::dispatch path,
// rotate_batch, rotate_soa, DenseRotation's planes stored past the caches) against the
// Ivanic-Ruedenberg reference and against themselves across thread counts; quaternions against
// Eigen's conversion. The run-time orders go through zhf::dispatch, where each order's kernels
// are compiled once per path, rather than instantiating every order here.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "dispatch_paths.h"
#include "test_support.h"
#include "test_tolerances.h"
#include "zhf/dispatch/rotator.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/orthogonal.h"
#include "zhf/runtime/pack.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/rotator.h"
#include "zhf/runtime/soa_batch.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"
#include "zhf_order2.h"
#include "zhf_order3.h"
#include "zhf_order4.h"
#include "zhf_order5.h"
#include "zhf_kernels.h"

namespace zhf {
namespace {

using namespace zhf::tolerance;

// count unit vectors of order N, flat.
template <class T>
std::vector<T> unit_vectors(std::size_t count, int order, std::mt19937_64& rng) {
  sh::Normal<> normal;
  const std::size_t n = std::size_t(order) * order;
  std::vector<T> out(count * n);
  for (std::size_t v = 0; v < count; ++v) {
    Eigen::VectorXd f(n);
    for (std::size_t i = 0; i < n; ++i) f[i] = normal(rng);
    f.normalize();
    for (std::size_t i = 0; i < n; ++i) out[v * n + i] = T(f[i]);
  }
  return out;
}

template <class T>
void check_shared(const std::string& path, int order, double tolerance) {
  std::mt19937_64 rng(order);
  const sh::RotationMatrix m = sh::random_rotation(rng);
  T r[9];
  for (int i = 0; i < 9; ++i) r[i] = T(m(i / 3, i % 3));
  const sh::BandMatrices exact = sh::ivanic_ruedenberg(m, order);
  const auto rotator = dispatch::Rotator<T>::make(order);
  const std::size_t n = std::size_t(order) * order;
  // Below N^2 vectors one by one, above it through the band matrices, above the thread threshold
  // on two threads.
  for (std::size_t count : {std::size_t(3), n + 1, runtime::kParallelBatchThreshold + 7}) {
    const std::vector<T> in = unit_vectors<T>(count, order, rng);
    std::vector<T> out(in.size()), one_thread(in.size());
    rotator.transform_shared(count, r, in.data(), out.data(), 2);
    rotator.transform_shared(count, r, in.data(), one_thread.data(), 1);
    ASSERT_EQ(out, one_thread) << path << ", order " << order << ", " << count << " vectors: the thread count changed the result";
    for (std::size_t v = 0; v < count; v += 1 + count / 16) {
      Eigen::VectorXd f(n);
      for (std::size_t i = 0; i < n; ++i) f[i] = double(in[v * n + i]);
      const Eigen::VectorXd g = sh::apply_band_matrices(exact, f);
      for (std::size_t i = 0; i < n; ++i)
        ASSERT_NEAR(double(out[v * n + i]), g[i], tolerance)
            << path << ", order " << order << ", band " << runtime::band_of(int(i)) << ", index " << i << ", vector " << v << " of "
            << count;
    }
  }
}

TEST(Batch, SharedRotationMatchesTheReferenceAtEveryGeneratedOrder) {
  test::on_every_dispatch_path([](const std::string& path) {
    for (int order = 2; order <= runtime::kMaxGeneratedOrder; ++order) {
      check_shared<double>(path, order, kDouble);
      check_shared<float>(path, order, kFloatRotation);
    }
  });
}

// Per-item transforms on a path (transform_each: rotations in runs through the per-item batch,
// SoA blocks where dispatch picks them; reflections and axis maps one by one) at every count
// 1..33, so every partial block and run, against the generated scalar kernel vector by vector
// (OrthogonalTransform over runtime::scalar_kernels), within the lanes-against-scalar bound (the
// kernels' contraction differs); the same through rotate_batch on rotations alone.
template <class T>
void check_each(const std::string& path, int order, double tolerance) {
  std::mt19937_64 rng(300 + order);
  const auto rotator = dispatch::Rotator<T>::make(order);
  const auto scalar = runtime::Rotator<T>::with(gen::scalar_kernels<T>(order));
  const std::size_t n = std::size_t(order) * order;
  for (std::size_t count = 1; count <= 33; ++count) {
    std::vector<T> q(9 * count), r(9 * count);
    for (std::size_t v = 0; v < count; ++v) {
      const sh::RotationMatrix m = sh::random_rotation(rng);
      // Every fifth a reflection, every seventh the y-x swap (an exact axis map), the rest rotations.
      const double sign = v % 5 == 4 ? -1 : 1;
      for (int k = 0; k < 9; ++k) q[9 * v + k] = T(sign * m(k / 3, k % 3)), r[9 * v + k] = T(m(k / 3, k % 3));
      if (v % 7 == 6) {
        const T swap[9] = {0, 1, 0, 1, 0, 0, 0, 0, 1};
        std::copy(swap, swap + 9, &q[9 * v]);
      }
    }
    const std::vector<T> in = unit_vectors<T>(count, order, rng);
    std::vector<T> each(in.size()), batch(in.size()), expected(in.size());
    rotator.transform_each(count, q.data(), in.data(), each.data(), 1);
    rotator.rotate_batch(count, r.data(), in.data(), batch.data(), 1);
    for (std::size_t v = 0; v < count; ++v) {
      runtime::OrthogonalTransform<T>(scalar, &q[9 * v]).apply(&in[n * v], &expected[n * v]);
      T single[runtime::kMaxGeneratedOrder * runtime::kMaxGeneratedOrder];
      scalar.rotate(&r[9 * v], &in[n * v], single);
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_NEAR(double(each[n * v + i]), double(expected[n * v + i]), tolerance)
            << path << ", transform_each, order " << order << ", band " << runtime::band_of(int(i)) << ", index " << i << ", vector " << v
            << " of " << count;
        ASSERT_NEAR(double(batch[n * v + i]), double(single[i]), tolerance)
            << path << ", rotate_batch, order " << order << ", band " << runtime::band_of(int(i)) << ", index " << i << ", vector " << v
            << " of " << count;
      }
    }
  }
}

TEST(Batch, PerItemTransformsMatchTheScalarKernelAtEveryCountTo33) {
  test::on_every_dispatch_path([](const std::string& path) {
    for (int order = 2; order <= runtime::kMaxGeneratedOrder; ++order) {
      check_each<double>(path, order, kDouble);
      check_each<float>(path, order, kFloatLobeStageWorstUnitInput);
    }
  });
}

// The bulk layouts of one rotation (random, identity, a half turn, a tiny turn): 3DGS's
// interleaved splats and planar arrays, in place and not, one and two threads, against the
// reference per channel. Counts not a multiple of the pack
// width, so the planar tail runs too.
template <class T>
void check_layouts(const std::string& path, int order, const sh::RotationMatrix& m, double tolerance) {
  std::mt19937_64 rng(100 + order);
  T r[9];
  for (int i = 0; i < 9; ++i) r[i] = T(m(i / 3, i % 3));
  const sh::BandMatrices exact = sh::ivanic_ruedenberg(m, order);
  const auto rotator = dispatch::Rotator<T>::make(order);
  const std::size_t n = std::size_t(order) * order, rest = n - 1, item = 3 * n;
  for (std::size_t count : {std::size_t(1), std::size_t(13), runtime::kParallelBatchThreshold + 5}) {
    const std::vector<T> channels = unit_vectors<T>(3 * count, order, rng);  // vector 3 v + c
    auto channel = [&](std::size_t v, int c) { return &channels[(3 * v + c) * n]; };
    std::vector<T> splats(count * item), planar(count * item);
    for (std::size_t v = 0; v < count; ++v)
      for (int c = 0; c < 3; ++c) {
        splats[item * v + c] = channel(v, c)[0];
        for (std::size_t i = 1; i < n; ++i) splats[item * v + 3 + c * rest + i - 1] = channel(v, c)[i];
        for (std::size_t i = 0; i < n; ++i) planar[(c * n + i) * count + v] = channel(v, c)[i];
      }
    std::vector<T> splats_out(splats.size()), planar_out(planar.size()), splats_in_place = splats, planar_in_place = planar;
    rotator.apply_splats(r, count, splats.data(), splats_out.data(), 2);
    rotator.apply_splats(r, count, splats_in_place.data(), splats_in_place.data(), 1);
    rotator.apply_planar(r, count, 3, planar.data(), planar_out.data(), 2);
    rotator.apply_planar(r, count, 3, planar_in_place.data(), planar_in_place.data(), 1);
    ASSERT_EQ(splats_out, splats_in_place) << path << ", order " << order << ": in place or the thread count changed the splats";
    ASSERT_EQ(planar_out, planar_in_place) << path << ", order " << order << ": in place or the thread count changed the planes";
    for (std::size_t v = 0; v < count; v += 1 + count / 16)
      for (int c = 0; c < 3; ++c) {
        Eigen::VectorXd f(n);
        for (std::size_t i = 0; i < n; ++i) f[i] = double(channel(v, c)[i]);
        const Eigen::VectorXd g = sh::apply_band_matrices(exact, f);
        for (std::size_t i = 0; i < n; ++i) {
          const double splat = i == 0 ? splats_out[item * v + c] : splats_out[item * v + 3 + c * rest + i - 1];
          const double plane = planar_out[(c * n + i) * count + v];
          ASSERT_NEAR(splat, g[i], tolerance) << path << ", splats, order " << order << ", band " << runtime::band_of(int(i))
                                              << ", index " << i << ", item " << v << ", channel " << c;
          ASSERT_NEAR(plane, g[i], tolerance) << path << ", planar, order " << order << ", band " << runtime::band_of(int(i))
                                              << ", index " << i << ", item " << v << ", channel " << c;
        }
      }
  }
}

TEST(Batch, BulkLayoutsMatchTheReferenceAtEveryGeneratedOrder) {
  std::mt19937_64 rng(7);
  const std::vector<sh::RotationMatrix> rotations = {sh::random_rotation(rng), sh::RotationMatrix::Identity(),
                                              sh::RotationMatrix(Eigen::AngleAxisd(runtime::kPi, Eigen::Vector3d(1, 1, 1).normalized())),
                                              sh::RotationMatrix(Eigen::AngleAxisd(1e-7, Eigen::Vector3d::UnitZ()))};
  test::on_every_dispatch_path([&](const std::string& path) {
    for (int order = 2; order <= runtime::kMaxGeneratedOrder; ++order)
      for (const sh::RotationMatrix& m : rotations) {
        check_layouts<double>(path, order, m, kDouble);
        check_layouts<float>(path, order, m, kFloatRotation);
      }
  });
}

// apply_planar on outputs large enough to be stored past the caches: the same bytes as in place
// (stored through the caches), on two threads, and the reference on a sample of items; and the
// cases that keep cached stores (in place, small, out not a whole number of lines from in, planes
// not whole lines apart).
template <class T>
void check_streamed_planar(double tolerance) {
  constexpr int kOrder = 4, kChannels = 3;
  constexpr std::size_t n = kOrder * kOrder, planes = kChannels * n;
  std::mt19937_64 rng(300);
  const sh::RotationMatrix m = sh::random_rotation(rng);
  T r[9];
  for (int i = 0; i < 9; ++i) r[i] = T(m(i / 3, i % 3));
  const runtime::DenseRotation<T> dense = runtime::Rotator<T>::template of<kOrder>().dense(r);
  // Just past the size, planes whole lines apart; in and out each from a line.
  const std::size_t line = runtime::kCacheLineBytes / sizeof(T), count = ((std::size_t(64) << 20) / sizeof(T) / planes / line + 1) * line,
                    size = planes * count;
  std::vector<T> buffer;
  const auto [in, out] = test::aligned_pair(buffer, size + line, runtime::kCacheLineBytes);
  sh::Normal<> normal;
  for (std::size_t i = 0; i < size; ++i) in[i] = T(normal(rng));
  ASSERT_TRUE(dense.planar_streams(count, kChannels, in, out)) << sizeof(T) << "-byte values";
  ASSERT_FALSE(dense.planar_streams(count, kChannels, in, in));
  ASSERT_FALSE(dense.planar_streams(count - line, kChannels, in, out));  // below the size, whole lines
  ASSERT_FALSE(dense.planar_streams(count, kChannels, in, out - 1));
  ASSERT_FALSE(dense.planar_streams(count + 1, kChannels, in, out));
  const std::vector<T> input(in, in + size);
  std::vector<T> in_place = input;
  dense.apply_planar(count, kChannels, in, out, 2);
  dense.apply_planar(count, kChannels, in_place.data(), in_place.data(), 1);
  ASSERT_TRUE(std::equal(in_place.begin(), in_place.end(), out)) << "stored past the caches or not, other bytes";
  dense.apply_planar(count, kChannels, in, out - 1, 1);  // cached stores, out a value short of a line
  ASSERT_TRUE(std::equal(in_place.begin(), in_place.end(), out - 1)) << "out a value short of a line, other bytes";
  ASSERT_TRUE(std::equal(input.begin(), input.end(), in)) << "the input changed";
  const sh::BandMatrices exact = sh::ivanic_ruedenberg(m, kOrder);
  for (std::size_t v = 0; v < count; v += count / 7)
    for (int c = 0; c < kChannels; ++c) {
      Eigen::VectorXd f(n);
      for (std::size_t i = 0; i < n; ++i) f[i] = double(input[(c * n + i) * count + v]);
      const Eigen::VectorXd g = sh::apply_band_matrices(exact, f);
      for (std::size_t i = 0; i < n; ++i)
        ASSERT_NEAR(double(in_place[(c * n + i) * count + v]), g[i], tolerance * f.norm())
            << "order " << kOrder << ", band " << runtime::band_of(int(i)) << ", index " << i << ", item " << v << ", channel " << c;
    }
}

TEST(Batch, LargePlanarOutputsStoredPastTheCachesKeepTheirBytes) {
  check_streamed_planar<float>(kFloatRotation);
  check_streamed_planar<double>(kDouble);
}

// rotate_soa against the reference and lane for lane against the scalar kernel, on random
// rotations and the adversarial ones (axes, half turns, near-identity), count of them, planes
// stride values apart (the values past count in the output planes left as they were). Float
// against the reference: the bound for any unit input of a float lobe stage.
template <int N, class T>
void check_soa(std::size_t count, double tolerance, std::size_t stride) {
  std::mt19937_64 rng(200 + N);
  std::vector<sh::RotationMatrix> rotations = {sh::RotationMatrix::Identity(), sh::RotationMatrix(Eigen::AngleAxisd(runtime::kPi, Eigen::Vector3d::UnitX())),
                                        sh::RotationMatrix(Eigen::AngleAxisd(runtime::kPi, Eigen::Vector3d(1, 1, 1).normalized())),
                                        sh::RotationMatrix(Eigen::AngleAxisd(1e-7, Eigen::Vector3d::UnitZ())),
                                        sh::RotationMatrix(Eigen::AngleAxisd(runtime::kPi / 2, Eigen::Vector3d::UnitY()))};
  while (rotations.size() < count) rotations.push_back(sh::random_rotation(rng));
  const std::size_t n = N * N;
  const std::vector<T> vectors = unit_vectors<T>(count, N, rng);
  std::vector<T> r(9 * stride), in(n * stride), out(n * stride, T(7)), two(n * stride);
  for (std::size_t v = 0; v < count; ++v) {
    for (int k = 0; k < 9; ++k) r[k * stride + v] = T(rotations[v](k / 3, k % 3));
    for (std::size_t i = 0; i < n; ++i) in[i * stride + v] = vectors[v * n + i];
  }
  if (stride == count)
    runtime::rotate_soa<N>(count, r.data(), in.data(), out.data(), 1);
  else
    runtime::rotate_soa<N>(count, stride, r.data(), in.data(), out.data(), 1);
  runtime::rotate_soa<N>(count, stride, r.data(), in.data(), two.data(), 2);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t v = count; v < stride; ++v) {
      ASSERT_EQ(out[i * stride + v], T(7)) << "order " << N << ": a value past count written, index " << i << ", place " << v;
      two[i * stride + v] = T(7);
    }
  ASSERT_EQ(out, two) << "order " << N << ": the thread count changed the result";
  for (std::size_t v = 0; v < count; ++v) {
    T rv[9], single[N * N];
    for (int k = 0; k < 9; ++k) rv[k] = r[k * stride + v];
    gen::Kernels<N>::template rotate<T>(rv, &vectors[v * n], single);
    Eigen::VectorXd f(n);
    for (std::size_t i = 0; i < n; ++i) f[i] = double(vectors[v * n + i]);
    sh::RotationMatrix exact_r;
    for (int k = 0; k < 9; ++k) exact_r(k / 3, k % 3) = double(rv[k]);
    const Eigen::VectorXd g = sh::apply_band_matrices(sh::ivanic_ruedenberg(exact_r, N), f);
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_NEAR(double(out[i * stride + v]), g[i], tolerance)
          << "order " << N << ", band " << runtime::band_of(int(i)) << ", index " << i << ", rotation " << v;
      ASSERT_NEAR(double(out[i * stride + v]), double(single[i]), tolerance)
          << "lanes against the scalar kernel, order " << N << ", index " << i << ", rotation " << v;
    }
  }
}

// The packs' reciprocal square root (vector instructions on x86) is the scalar kernel's, lane for
// lane and bit for bit, so rotate_soa's lanes equal the scalar kernel's up to contraction.
template <class T>
void check_reciprocal_sqrt() {
  using P = runtime::Pack<T>;
  std::mt19937_64 rng(11);
  std::vector<T> values = {T(1), T(4), T(2), T(0.5), T(1e-30), T(1e30), std::numeric_limits<T>::min(),
                           std::numeric_limits<T>::denorm_min(), std::numeric_limits<T>::max()};
  while (values.size() % P::kLanes != 0 || values.size() < 64)
    values.push_back(T(std::ldexp(double(rng() >> 11) / 9007199254740992.0 + 0.5, int(rng() % 40) - 20)));
  for (std::size_t first = 0; first < values.size(); first += P::kLanes) {
    T lanes[P::kLanes];
    reciprocal_sqrt(P::load(&values[first])).store(lanes);
    for (int k = 0; k < P::kLanes; ++k)
      ASSERT_EQ(lanes[k], T(1) / std::sqrt(values[first + k])) << "x = " << values[first + k] << ", lane " << k;
  }
}

TEST(Batch, PackReciprocalSquareRootIsTheScalarOne) {
  check_reciprocal_sqrt<float>();
  check_reciprocal_sqrt<double>();
}

// Both ways rotate_soa reads its inputs, on counts past the threshold (so the two-thread run
// splits the batch): 5 past a multiple of 8 lanes, planes spread over the cache sets (read
// straight from the planes up to kSoaDirectMaxOrder), and planes a whole set span apart (copied
// through the block).
template <int N, class T>
void check_soa_counts(double tolerance) {
  const std::size_t spread = runtime::kParallelBatchThreshold + 5,
                    crowded = runtime::kParallelBatchThreshold + runtime::kCacheSetSpanBytes / sizeof(T);
  const bool reads_spread_directly = runtime::soa_detail::reads_planes_directly<N, T>(spread),
             reads_crowded_directly = runtime::soa_detail::reads_planes_directly<N, T>(crowded);
  EXPECT_EQ(reads_spread_directly, N <= runtime::soa_detail::kSoaDirectMaxOrder) << "order " << N;
  EXPECT_FALSE(reads_crowded_directly) << "order " << N;
  check_soa<N, T>(spread, tolerance, spread);
  check_soa<N, T>(crowded, tolerance, crowded);
  // The crowded count on planes padded to a stride that spreads them (the same stride above
  // kSoaDirectMaxOrder, where they are copied anyway), and the spread one on planes 3 values past
  // count apart (not a whole number of packs).
  const std::size_t padded = runtime::soa_plane_stride<N, T>(crowded);
  EXPECT_EQ(padded > crowded, N <= runtime::soa_detail::kSoaDirectMaxOrder) << "order " << N << ", stride " << padded;
  EXPECT_EQ((runtime::soa_detail::reads_planes_directly<N, T>(padded)), N <= runtime::soa_detail::kSoaDirectMaxOrder)
      << "order " << N << ", stride " << padded;
  if (padded > crowded) check_soa<N, T>(crowded, tolerance, padded);
  check_soa<N, T>(spread, tolerance, spread + 3);
}

TEST(Batch, AcrossRotationsMatchesTheReferenceAndTheScalarKernel) {
  check_soa_counts<2, float>(kFloatLobeStageWorstUnitInput);
  check_soa_counts<3, float>(kFloatLobeStageWorstUnitInput);
  check_soa_counts<4, float>(kFloatLobeStageWorstUnitInput);
  check_soa_counts<5, float>(kFloatLobeStageWorstUnitInput);
  check_soa_counts<2, double>(kDouble);
  check_soa_counts<3, double>(kDouble);
  check_soa_counts<4, double>(kDouble);
}

// planes_per_set against counts worked by hand: 4000 floats apart is 3712 bytes past a set
// span, so 18 planes sit 384 bytes apart (mod 4096) and never two in one line-wide window.
TEST(Batch, PlanesPerSetCountsCrowdedPlanes) {
  EXPECT_EQ(runtime::soa_detail::planes_per_set(4000, 18, sizeof(float)), 1);
  EXPECT_EQ(runtime::soa_detail::planes_per_set(4096, 18, sizeof(float)), 18);
  EXPECT_EQ(runtime::soa_detail::planes_per_set(2048, 18, sizeof(double)), 18);
  EXPECT_EQ(runtime::soa_detail::planes_per_set(4608, 18, sizeof(float)), 9);   // 2048 bytes: two places
  EXPECT_EQ(runtime::soa_detail::planes_per_set(4100, 18, sizeof(float)), 4);   // 16 bytes apart
  EXPECT_EQ(runtime::soa_detail::planes_per_set(1, 18, sizeof(float)), 16);     // 4 bytes apart: 16 in a line
  EXPECT_EQ(runtime::soa_detail::planes_per_set(1023, 18, sizeof(float)), 16);  // 4 bytes apart, downwards
  EXPECT_EQ(runtime::soa_detail::planes_per_set(4112, 18, sizeof(float), 128), 2);  // 64 bytes apart, two-line windows
  EXPECT_EQ(runtime::soa_detail::planes_per_set(4128, 18, sizeof(float), 128), 1);  // 128 bytes apart
}

// soa_plane_stride against strides worked by hand (4128 floats: the planes 128 bytes apart
// within the set span), and over every count to 5000: never below count, read directly, and where
// padded a whole number of lines, within a set span of count, each plane two lines or more from
// the next. Strides below count and offsets past a size_t refused.
TEST(Batch, PlaneStrideSpreadsThePlanes) {
  EXPECT_EQ((runtime::soa_plane_stride<3, float>(4096)), 4128u);
  EXPECT_EQ((runtime::soa_plane_stride<3, float>(4095)), 4128u);
  EXPECT_EQ((runtime::soa_plane_stride<3, float>(4000)), 4000u);
  EXPECT_EQ((runtime::soa_plane_stride<2, float>(1024)), 1056u);
  EXPECT_EQ((runtime::soa_plane_stride<4, double>(2048)), 2064u);
  EXPECT_EQ((runtime::soa_plane_stride<5, float>(4096)), 4096u);
  const std::size_t line = runtime::kCacheLineBytes / sizeof(float), span = runtime::kCacheSetSpanBytes / sizeof(float);
  for (std::size_t count = 0; count <= 5000; ++count) {
    const std::size_t stride = runtime::soa_plane_stride<3, float>(count);
    ASSERT_TRUE((runtime::soa_detail::reads_planes_directly<3, float>(stride))) << "count " << count << ", stride " << stride;
    if (stride == count) continue;
    ASSERT_GT(stride, count);
    ASSERT_EQ(stride % line, 0u) << "count " << count << ", stride " << stride;
    ASSERT_LE(stride - count, span) << "count " << count << ", stride " << stride;
    ASSERT_EQ(runtime::soa_detail::planes_per_set(stride, 18, sizeof(float), 2 * runtime::kCacheLineBytes), 1)
        << "count " << count << ", stride " << stride;
  }
  std::vector<float> r(9 * 16), in(9 * 16), out(9 * 16);
  EXPECT_THROW(runtime::rotate_soa<3>(16, 15, r.data(), in.data(), out.data()), std::invalid_argument);
  const std::size_t most = std::numeric_limits<std::size_t>::max();
  EXPECT_THROW(runtime::rotate_soa<3>(16, most / 18 + 1, r.data(), in.data(), out.data()), std::invalid_argument);
  EXPECT_THROW((runtime::soa_plane_stride<3, float>(most / span * span)), std::invalid_argument);  // crowded
  EXPECT_EQ(out, std::vector<float>(9 * 16));
}

TEST(Batch, PerVectorRotationsDoNotDependOnTheThreadCount) {
  constexpr int kOrder = 5;
  std::mt19937_64 rng(5);
  const std::size_t count = runtime::kParallelBatchThreshold * 2 + 3, n = kOrder * kOrder;
  std::vector<float> r(9 * count);
  for (std::size_t v = 0; v < count; ++v) {
    const sh::RotationMatrix m = sh::random_rotation(rng);
    for (int i = 0; i < 9; ++i) r[9 * v + i] = float(m(i / 3, i % 3));
  }
  const std::vector<float> in = unit_vectors<float>(count, kOrder, rng);
  std::vector<float> two(in.size()), one(in.size()), single(n);
  const auto rotator = runtime::Rotator<float>::of<kOrder>();
  rotator.rotate_batch(count, r.data(), in.data(), two.data(), 2);
  rotator.rotate_batch(count, r.data(), in.data(), one.data(), 1);
  ASSERT_EQ(two, one);
  rotator.rotate(r.data() + 9 * (count - 1), in.data() + n * (count - 1), single.data());
  for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(two[n * (count - 1) + i], single[i]) << "index " << i;
}

TEST(Batch, QuaternionsGiveEigensRotation) {
  std::mt19937_64 rng(6);
  sh::Normal<> normal;
  for (int k = 0; k < 200; ++k) {
    const double scale = std::pow(10.0, 100 * (k % 7 - 3));  // lengths from 1e-300 to 1e300
    const Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
    const sh::RotationMatrix expected = q.normalized().toRotationMatrix();
    const Eigen::Vector4d s = q.coeffs() * scale;  // x, y, z, w
    runtime::Matrix3 r, negated;
    ASSERT_TRUE(runtime::rotation_from_quaternion(s[3], s[0], s[1], s[2], r));
    ASSERT_TRUE(runtime::rotation_from_quaternion(-s[3], -s[0], -s[1], -s[2], negated));
    for (int i = 0; i < 9; ++i) {
      ASSERT_NEAR(r[i], expected(i / 3, i % 3), kExactToRounding * 4) << "quaternion " << k << ", entry " << i;
      ASSERT_EQ(r[i], negated[i]) << "q and -q differ at entry " << i;
    }
  }
  runtime::Matrix3 untouched{};
  EXPECT_FALSE(runtime::rotation_from_quaternion(0, 0, 0, 0, untouched));
  EXPECT_FALSE(runtime::rotation_from_quaternion(std::numeric_limits<double>::quiet_NaN(), 0, 0, 1, untouched));
  EXPECT_FALSE(runtime::rotation_from_quaternion(std::numeric_limits<double>::infinity(), 0, 0, 1, untouched));
  EXPECT_EQ(untouched, runtime::Matrix3{});
}

}  // namespace
}  // namespace zhf
