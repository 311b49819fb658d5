// No rotate call allocates once its rotator is built: every global allocation in this program is
// counted, and each path is called after construction with the count watched: the header-only
// rotators, and the compiled library's (zhf::dispatch) on every instruction-set path this CPU runs.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "dispatch_paths.h"
#include "test_support.h"
#include "zhf/dispatch/rotator.h"
#include "zhf/runtime/lanes.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/table_io.h"
#include "zhf/runtime/rotator.h"
#include "zhf/runtime/soa_batch.h"
#include "zhf/sh/random.h"
#include "zhf_order2.h"
#include "zhf_order4.h"
#include "zhf_order5.h"

namespace {
std::atomic<long> allocations{0};
}  // namespace

// The replacements pair malloc with free by design; GCC, seeing both inlined, takes free for a
// mismatch with new.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

void* operator new(std::size_t size) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
// Over-aligned types (the SIMD packs a rotator holds) come through the aligned form.
void* operator new(std::size_t size, std::align_val_t align) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  const std::size_t a = static_cast<std::size_t>(align), rounded = (size + a - 1) / a * a;
  if (void* p = std::aligned_alloc(a, rounded ? rounded : a)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace zhf {
namespace {

template <class T>
struct Data {
  std::vector<T> r, in, out;
  Data(int order, std::size_t count) : r(9 * count), in(3 * order * order * count), out(in.size()) {
    std::mt19937_64 rng(order);
    sh::Normal<> normal;
    for (std::size_t v = 0; v < count; ++v) {  // rotations about z by random angles
      const double a = normal(rng), c = std::cos(a), s = std::sin(a);
      const T m[9] = {T(c), T(-s), 0, T(s), T(c), 0, 0, 0, 1};
      std::copy(m, m + 9, &r[9 * v]);
    }
    for (T& x : in) x = T(normal(rng));
  }
};

// Calls call() and reports the allocations it made.
template <class Call>
long allocations_of(Call&& call) {
  const long before = allocations.load();
  call();
  return allocations.load() - before;
}

constexpr std::size_t kVectors = 64;

// The rotate, RGB and one-thread batch calls of a rotator of either kind (the header-only one or
// the compiled library's, whose bulk layouts build the transform's band matrices per call, by
// design); returns its data for further calls.
template <class T, template <class> class AnyRotator>
Data<T> check_rotate_calls(const AnyRotator<T>& rotator, const std::string& name) {
  const int order = rotator.order();
  Data<T> d(order, kVectors);
  EXPECT_EQ(allocations_of([&] { rotator.rotate(d.r.data(), d.in.data(), d.out.data()); }), 0) << name << " rotate, order " << order;
  EXPECT_EQ(allocations_of([&] { rotator.rotate_rgb(d.r.data(), d.in.data(), d.out.data()); }), 0)
      << name << " rotate_rgb, order " << order;
  EXPECT_EQ(allocations_of([&] { rotator.rotate_batch(kVectors, d.r.data(), d.in.data(), d.out.data(), 1); }), 0)
      << name << " rotate_batch on one thread, order " << order;
  return d;
}

template <class T>
void check_rotator(const runtime::Rotator<T>& rotator, const std::string& name) {
  const int order = rotator.order();
  Data<T> d = check_rotate_calls(rotator, name);
  const runtime::DenseRotation<T> dense = rotator.dense(d.r.data());
  EXPECT_EQ(allocations_of([&] { dense.apply(d.in.data(), d.out.data()); }), 0) << name << " dense apply, order " << order;
  EXPECT_EQ(allocations_of([&] { dense.apply_splats(kVectors / 3, d.in.data(), d.out.data(), 1); }), 0)
      << name << " apply_splats, order " << order;
  EXPECT_EQ(allocations_of([&] { dense.apply_planar(kVectors, 1, d.in.data(), d.out.data(), 1); }), 0)
      << name << " apply_planar, order " << order;
}

template <int... N>
void check_generated_orders(std::integer_sequence<int, N...>) {
  (check_rotator(runtime::Rotator<float>::of<N>(), "generated float"), ...);
  (check_rotator(runtime::Rotator<double>::of<N>(), "generated double"), ...);
}

TEST(NoAllocation, TheCounterSeesAllocations) {
  EXPECT_GT(allocations_of([] { std::vector<int> v(10); }), 0);
  struct alignas(64) Wide {
    float x[16];
  };
  EXPECT_GT(allocations_of([] { std::vector<Wide> v(3); }), 0);
}

TEST(NoAllocation, PlanarStoredPastTheCachesDoesNotAllocate) {
  // Three channels of order 4 just past the size apply_planar stores past the caches.
  const std::size_t line = runtime::kCacheLineBytes / sizeof(float), count = ((std::size_t(64) << 20) / sizeof(float) / 48 / line + 1) * line;
  Data<float> d(4, 1);
  std::vector<float> buffer;
  const std::pair<float*, float*> planes = test::aligned_pair(buffer, 48 * count, runtime::kCacheLineBytes);
  float* const in = planes.first;  // a variable of its own: a lambda may not capture a structured binding
  float* const out = planes.second;
  const runtime::DenseRotation<float> dense = runtime::Rotator<float>::of<4>().dense(d.r.data());
  ASSERT_TRUE(dense.planar_streams(count, 3, in, out));
  EXPECT_EQ(allocations_of([&] { dense.apply_planar(count, 3, in, out, 1); }), 0);
}

TEST(NoAllocation, AcrossRotationsDoesNotAllocate) {
  // Single steps only; blocks read straight from the planes; blocks copied (planes 16 KiB apart).
  for (const std::size_t count : {21, 4000, 4096}) {
    Data<float> d(4, count);
    EXPECT_EQ(allocations_of([&] { runtime::rotate_soa<4>(count, d.r.data(), d.in.data(), d.out.data(), 1); }), 0)
        << count << " rotations";
  }
  // The same 4096 on planes padded to a stride that spreads them.
  const std::size_t count = 4096, stride = runtime::soa_plane_stride<4, float>(count);
  Data<float> d(4, stride);
  EXPECT_EQ(allocations_of([&] { runtime::rotate_soa<4>(count, stride, d.r.data(), d.in.data(), d.out.data(), 1); }), 0);
}

TEST(NoAllocation, NoRotateCallAllocatesAfterConstruction) {
  // The header-only kernels at the orders where the paths change (bands 0 and 1, lanes, band rows
  // where the build has them); every order on every compiled path.
  check_generated_orders(std::integer_sequence<int, 2, 4, 5>());
  test::on_every_dispatch_path([](const std::string& path) {
    for (const int order : {1, 2, 3, 4, 5, 6, 7, 8, 9, 40}) {
      check_rotate_calls(dispatch::Rotator<float>::make(order), path + " float");
      check_rotate_calls(dispatch::Rotator<double>::make(order), path + " double");
    }
  });
  for (int order : {3, 8, 12, 16, 32}) {
    const runtime::LobeTable table =
        runtime::read_lobe_table(test::checked_in_table(order));
    check_rotator(runtime::Rotator<float>::from_table(table), "table float");
    check_rotator(runtime::Rotator<double>::from_table(table), "table double");
  }
  for (int order : {9, 40}) {  // beyond the tables (its dense band matrices too)
    check_rotator(runtime::Rotator<float>::zxzxz(order), "zxzxz float");
    check_rotator(runtime::Rotator<double>::zxzxz(order), "zxzxz double");
  }
}

}  // namespace
}  // namespace zhf
