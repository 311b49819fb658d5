// zhf::dispatch: each instruction-set path this CPU runs, forced in turn, against the recurrence
// in long double at every generated order and at runtime orders beyond them, float and double,
// on the extreme rotations and random ones; reflections, shared transforms and the bulk layouts
// against the single-vector path; the finite check of every path; a path the CPU lacks or the
// library does not have refused in one line, by the call and through ZHF_ISA in the CLI.
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "test_tolerances.h"
#include "zhf/dispatch/checks.h"
#include "zhf/dispatch/rotator.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/runtime/table_io.h"
#include "zhf/runtime/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/rotation_matrix.h"

namespace zhf {
namespace {

using dispatch::Isa;
using dispatch::Rotator;

// Restores the path in use when a test that forces paths ends.
class DispatchTest : public ::testing::Test {
 protected:
  void TearDown() override { dispatch::use_isa(dispatch::isa_name(dispatch::supported_isas().front())); }
};

// The worst error of rotator on a random unit vector under r against the recurrence in long
// double; at: the coefficient where it is.
template <class T>
double worst_error(const Rotator<T>& rotator, const sh::RotationMatrix& r, std::mt19937_64& rng, int& at) {
  const int order = rotator.order(), n = order * order;
  sh::Normal<> normal;
  std::vector<double> f(n);
  double norm = 0;
  for (double& x : f) x = normal(rng), norm += x * x;
  std::vector<T> rt(9), in(n), out(n);
  for (int i = 0; i < 9; ++i) rt[i] = T(r(i / 3, i % 3));
  for (int i = 0; i < n; ++i) in[i] = T(f[i] / std::sqrt(norm)), f[i] = double(in[i]);
  rotator.rotate(rt.data(), in.data(), out.data());
  return test::worst_against_recurrence(r.data(), order, f, out.data(), at);
}

template <class T>
void check_every_order(const std::string& isa) {
  const char* type = std::is_same_v<T, float> ? "float" : "double";
  std::mt19937_64 rng(54);
  for (int order : {1, 2, 3, 4, 5, 6, 7, 8, 9, 16, 32}) {
    const Rotator<T> rotator = Rotator<T>::make(order);
    ASSERT_EQ(dispatch::isa_name(rotator.isa()), isa);
    std::vector<std::pair<std::string, sh::RotationMatrix>> rotations = sh::extreme_rotations({});
    for (int k = 0; k < 20; ++k) rotations.push_back({"random " + std::to_string(k), sh::random_rotation(rng)});
    for (const auto& [name, r] : rotations) {
      int at = 0;
      EXPECT_LE(worst_error(rotator, r, rng, at), test::rotation_tolerance<T>(order))
          << isa << " (" << rotator.path() << "), " << type << ", order " << order << ", rotation '" << name << "', band "
          << runtime::band_of(at) << ", index " << at;
    }
  }
}

TEST_F(DispatchTest, EveryPathThisCpuRunsMatchesTheReferenceAtEveryOrder) {
  const std::vector<Isa> isas = dispatch::supported_isas();
  ASSERT_FALSE(isas.empty());
  // Set where the CPU is known (an emulated one): the paths it must find, fastest first.
  if (const char* expected = std::getenv("ZHF_TEST_EXPECTED_PATHS")) {
    std::string found;
    for (Isa isa : isas) found += (found.empty() ? "" : ",") + std::string(dispatch::isa_name(isa));
    ASSERT_EQ(found, expected);
  }
  for (Isa isa : isas) {
    dispatch::use_isa(dispatch::isa_name(isa));
    ASSERT_EQ(dispatch::active_isa(), isa);
    check_every_order<float>(dispatch::isa_name(isa));
    check_every_order<double>(dispatch::isa_name(isa));
  }
}

// Random unit vectors of an order, count of them.
template <class T>
std::vector<T> random_vectors(int order, std::size_t count, std::mt19937_64& rng) {
  sh::Normal<> normal;
  std::vector<T> v(count * order * order);
  for (T& x : v) x = T(normal(rng) / order);
  return v;
}

// The batch, reflection, shared and bulk entry points of every path against its rotate().
template <class T>
void check_entry_points(const std::string& isa, int order) {
  const std::string where = isa + ", order " + std::to_string(order) + (std::is_same_v<T, float> ? ", float" : ", double");
  const double tol = std::is_same_v<T, float> ? runtime::tolerance::kFloatRotation : runtime::tolerance::kDouble;
  // rotate_batch may run other kernels than rotate (SoA blocks of the generated kernel): the
  // bound between two float kernels' results on unit inputs.
  const double kernels_tol = std::is_same_v<T, float> ? tolerance::kFloatLobeStageWorstUnitInput : runtime::tolerance::kDouble;
  std::mt19937_64 rng(540 + order);
  const Rotator<T> rotator = Rotator<T>::make(order);
  const std::size_t n = std::size_t(order) * order, count = 300;  // past the batch threshold of one thread
  const std::vector<T> in = random_vectors<T>(order, count, rng);
  std::vector<T> rs(9 * count), qs(9 * count);
  for (std::size_t v = 0; v < count; ++v) {
    const sh::RotationMatrix r = sh::random_rotation(rng);
    for (int i = 0; i < 9; ++i) rs[9 * v + i] = T(r(i / 3, i % 3)), qs[9 * v + i] = (v % 2 ? -1 : 1) * rs[9 * v + i];
  }
  std::vector<T> batch(n * count), each(n * count), shared(n * count), one(n);
  rotator.rotate_batch(count, rs.data(), in.data(), batch.data(), 2);
  rotator.transform_each(count, qs.data(), in.data(), each.data(), 2);
  rotator.transform_shared(count, qs.data() + 9, in.data(), shared.data(), 2);
  const std::vector<std::vector<T>> bands = rotator.band_matrices(qs.data() + 9);
  // Prepared from a rotator gone by the time it is applied: the same values as transform_shared.
  std::vector<T> prepared(n * count);
  Rotator<T>::make(order).prepare(qs.data() + 9, count).apply(count, in.data(), prepared.data(), 1);
  for (std::size_t i = 0; i < n * count; ++i)
    ASSERT_EQ(prepared[i], shared[i]) << where << ": prepare, vector " << i / n << ", index " << i % n;
  for (std::size_t v = 0; v < count; ++v) {
    rotator.rotate(rs.data() + 9 * v, in.data() + n * v, one.data());
    for (std::size_t i = 0; i < n; ++i) {
      const int l = runtime::band_of(int(i));
      ASSERT_NEAR(batch[n * v + i], one[i], kernels_tol) << where << ": rotate_batch, vector " << v << ", band " << l << ", index " << i;
      // q = -R on odd vectors: the rotation's odd bands negated (those through rotate itself);
      // the rotations through the batch.
      if (v % 2) {
        ASSERT_EQ(each[n * v + i], l % 2 ? -one[i] : one[i]) << where << ": transform_each, vector " << v << ", band " << l << ", index " << i;
      } else {
        ASSERT_EQ(each[n * v + i], batch[n * v + i]) << where << ": transform_each, vector " << v << ", band " << l << ", index " << i;
      }
    }
    // Vector v under the shared q (-R_1): through its band matrices.
    for (int l = 0; l < order; ++l) {
      const int size = 2 * l + 1;
      for (int i = 0; i < size; ++i) {
        double expected = 0;
        for (int j = 0; j < size; ++j) expected += double(bands[l][i * size + j]) * double(in[n * v + l * l + j]);
        ASSERT_NEAR(shared[n * v + l * l + i], expected, tol) << where << ": transform_shared, vector " << v << ", band " << l
                                                                << ", index " << l * l + i;
      }
    }
  }
  // The 3DGS layout and planes under one q: three channels of every vector, against transform_shared.
  std::vector<T> splats(3 * n * count), planes(3 * n * count), splats_out(3 * n * count), planes_out(3 * n * count);
  const std::vector<T> rgb = random_vectors<T>(order, 3 * count, rng);
  std::vector<T> expected(3 * n * count);
  rotator.transform_shared(3 * count, qs.data() + 9, rgb.data(), expected.data(), 1);
  for (std::size_t v = 0; v < count; ++v)
    for (int c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < n; ++i) {
        const T x = rgb[(3 * v + c) * n + i];
        splats[3 * n * v + (i == 0 ? c : 3 + c * (n - 1) + i - 1)] = x;
        planes[(c * n + i) * count + v] = x;
      }
  rotator.apply_splats(qs.data() + 9, count, splats.data(), splats_out.data(), 2);
  rotator.apply_planar(qs.data() + 9, count, 3, planes.data(), planes_out.data(), 2);
  for (std::size_t v = 0; v < count; ++v)
    for (int c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < n; ++i) {
        const T e = expected[(3 * v + c) * n + i];
        const int l = runtime::band_of(int(i));
        ASSERT_NEAR(splats_out[3 * n * v + (i == 0 ? c : 3 + c * (n - 1) + i - 1)], e, tol)
            << where << ": apply_splats, item " << v << ", channel " << c << ", band " << l << ", index " << i;
        ASSERT_NEAR(planes_out[(c * n + i) * count + v], e, tol)
            << where << ": apply_planar, item " << v << ", channel " << c << ", band " << l << ", index " << i;
      }
}

TEST_F(DispatchTest, BatchReflectionSharedAndBulkCallsAgreeWithOneVectorOnEveryPath) {
  for (Isa isa : dispatch::supported_isas()) {
    dispatch::use_isa(dispatch::isa_name(isa));
    for (int order : {2, 3, 4, 5, 8, 12}) {
      check_entry_points<float>(dispatch::isa_name(isa), order);
      check_entry_points<double>(dispatch::isa_name(isa), order);
    }
  }
}

// A NaN or an infinity at each place of runs of every length up to a few vector widths (the
// vectorised body and its tail), and their finite runs, on every path.
template <class T>
void check_all_finite(const char* isa) {
  const char* type = std::is_same_v<T, float> ? "float" : "double";
  for (std::size_t count = 0; count <= 70; ++count) {
    std::vector<T> values(count);
    for (std::size_t i = 0; i < count; ++i) values[i] = T(i) - T(30.5);
    ASSERT_TRUE(dispatch::all_finite(values.data(), count)) << isa << ", " << type << ", " << count << " finite values";
    for (std::size_t at = 0; at < count; ++at)
      for (T bad : {std::numeric_limits<T>::quiet_NaN(), std::numeric_limits<T>::infinity(), -std::numeric_limits<T>::infinity()}) {
        const T kept = values[at];
        values[at] = bad;
        ASSERT_FALSE(dispatch::all_finite(values.data(), count)) << isa << ", " << type << ", " << bad << " at " << at << " of " << count;
        values[at] = kept;
      }
  }
  const T largest[] = {std::numeric_limits<T>::max(), -std::numeric_limits<T>::max(), std::numeric_limits<T>::denorm_min()};
  EXPECT_TRUE(dispatch::all_finite(largest, 3)) << isa << ", " << type << ": the largest and the smallest finite values";
}

TEST_F(DispatchTest, AllFiniteFindsEveryNonFiniteValueOnEveryPath) {
  for (Isa isa : dispatch::supported_isas()) {
    dispatch::use_isa(dispatch::isa_name(isa));
    check_all_finite<float>(dispatch::isa_name(isa));
    check_all_finite<double>(dispatch::isa_name(isa));
  }
}

TEST_F(DispatchTest, UnknownPathsAndPathsTheCpuLacksAreRefusedInOneLine) {
  auto refusal = [](const std::string& name) {
    try {
      dispatch::use_isa(name);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string unknown = refusal("sse9\n");
  EXPECT_NE(unknown.find("use_isa: 'sse9\\x0a' is not one of this build's paths ("), std::string::npos) << unknown;
  EXPECT_EQ(unknown.find('\n'), std::string::npos);
  const Isa before = dispatch::active_isa();
  for (const char* name : {"avx512", "avx2", "sse2", "neon", "generic"}) {
    bool supported = false;
    for (Isa isa : dispatch::supported_isas()) supported = supported || name == std::string(dispatch::isa_name(isa));
    if (supported) continue;
    const std::string message = refusal(name);
    EXPECT_FALSE(message.empty()) << name << " was accepted";
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(dispatch::active_isa(), before) << "a refused " << name << " changed the path";
  }
  EXPECT_THROW(Rotator<float>::make(0), std::invalid_argument);
  EXPECT_THROW(Rotator<double>::make(runtime::kMaxZxzxzOrder + 1), std::invalid_argument);
}

// make(order, &table): the table's rotation on each path, within the path's tolerance; a table of
// another order is refused.
TEST_F(DispatchTest, ALobeTableRotatesOnEveryPath) {
  std::mt19937_64 rng(55);
  for (Isa isa : dispatch::supported_isas()) {
    dispatch::use_isa(dispatch::isa_name(isa));
    for (int order : {3, 9, 16}) {
      const runtime::LobeTable table = runtime::read_lobe_table(test::checked_in_table(order), order);
      const auto f = Rotator<float>::make(order, &table);
      const auto d = Rotator<double>::make(order, &table);
      ASSERT_EQ(f.isa(), isa);
      for (int k = 0; k < 5; ++k) {
        const sh::RotationMatrix r = sh::random_rotation(rng);
        int at = 0;
        EXPECT_LE(worst_error(f, r, rng, at), test::rotation_tolerance<float>(order))
            << dispatch::isa_name(isa) << " (" << f.path() << "), float, order " << order << ", band " << runtime::band_of(at) << ", index " << at;
        EXPECT_LE(worst_error(d, r, rng, at), test::rotation_tolerance<double>(order))
            << dispatch::isa_name(isa) << " (" << d.path() << "), double, order " << order << ", band " << runtime::band_of(at) << ", index " << at;
      }
    }
    const runtime::LobeTable nine = runtime::read_lobe_table(test::checked_in_table(9), 9);
    EXPECT_THROW(Rotator<double>::make(10, &nine), runtime::InputError);
  }
}

// zhf rotate goes through zhf::dispatch at every order and names the path and kernels it took:
// those this process's dispatch picks on the same path.
TEST_F(DispatchTest, ZhfRotateTakesTheDispatchPathAtEveryOrder) {
  if (test::zhf_binary().empty()) GTEST_SKIP() << "this build has no zhf binary (the runtime alone)";
  const test::TempDir dir;
  for (int order : {5, 16, 40}) {
    const std::string in = (dir / "in.json").string(), out = (dir / "out.json").string();
    std::string vector = "[[1";  // band 0 alone: any rotation keeps it
    for (int i = 1; i < order * order; ++i) vector += ",0";
    test::write_text(in, vector + "]]");
    for (Isa isa : dispatch::supported_isas()) {
      const std::string name = dispatch::isa_name(isa);
      dispatch::use_isa(name);
      const std::string expected = name + " path, " + Rotator<double>::make(order).path() + " kernels";
      const test::RunResult r = test::run_zhf({"rotate", "--coeffs", in, "--zyz", "0.1 0.2 0.3", "--out", out}, "", {"ZHF_ISA=" + name});
      ASSERT_EQ(r.exit_code, 0) << r.err;
      EXPECT_NE(r.out.find("(order " + std::to_string(order) + ", 1 channel; " + expected + ")"), std::string::npos)
          << "order " << order << ": " << r.out << "lacks " << expected;
      if (order > runtime::kMaxGeneratedOrder) {
        EXPECT_EQ(Rotator<double>::make(order).path(), "zxzxz") << "order " << order;
      }
    }
  }
}

TEST_F(DispatchTest, TheCliNamesItsPathAndRefusesAWrongZhfIsa) {
  if (test::zhf_binary().empty()) GTEST_SKIP() << "this build has no zhf binary (the runtime alone)";
  const std::string fastest = dispatch::isa_name(dispatch::supported_isas().front());
  const test::RunResult version = test::run_zhf(std::string("--version"));
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_NE(version.out.find("rotation path " + fastest), std::string::npos) << version.out;
  for (Isa isa : dispatch::supported_isas()) {
    const test::RunResult forced = test::run_zhf({"--version"}, "", {"ZHF_ISA=" + std::string(dispatch::isa_name(isa))});
    EXPECT_NE(forced.out.find(std::string("rotation path ") + dispatch::isa_name(isa)), std::string::npos) << forced.out;
  }
  // --verbose: each order's kernels, as this process's zhf::dispatch picks them on the same path.
  const test::RunResult verbose = test::run_zhf(std::string("--version --verbose"));
  EXPECT_EQ(verbose.exit_code, 0) << verbose.err;
  for (int order : {1, 2, 3, 8, 9, 16, 32, 128}) {
    const std::string line = "order " + std::to_string(order) + ": float " + Rotator<float>::make(order).path() + ", double " +
                             Rotator<double>::make(order).path() + "\n";
    EXPECT_NE(verbose.out.find(line), std::string::npos) << verbose.out << "lacks " << line;
  }
  const test::RunResult wrong = test::run_zhf({"--version"}, "", {"ZHF_ISA=avx1024"});
  EXPECT_EQ(wrong.exit_code, 2);
  EXPECT_EQ(test::line_count(wrong.err), 1) << wrong.err;
  EXPECT_NE(wrong.err.find("ZHF_ISA: 'avx1024' is not one of this build's paths"), std::string::npos) << wrong.err;
}

}  // namespace
}  // namespace zhf
