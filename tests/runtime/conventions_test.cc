// Orthogonal transforms (reflections, exact axis maps), Euler angles and the convention presets,
// each checked as a function: g(w) = f(Q^T w) pointwise, and every preset against its system's
// own basis formula, written out here from that system's source (docs/conventions.md).
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "sh_bases.h"

#include "zhf/runtime/conventions.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/orthogonal.h"
#include "zhf/runtime/rotator.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/rotation_matrix.h"
#include "zhf_kernels.h"
#include "test_tolerances.h"

namespace zhf {
namespace {

using namespace zhf::tolerance;
using runtime::Matrix3;

std::vector<double> random_unit(int order, std::mt19937_64& rng) {
  sh::Normal<> normal;
  std::vector<double> f(order * order);
  double norm = 0;
  for (double& x : f) {
    x = normal(rng);
    norm += x * x;
  }
  for (double& x : f) x /= std::sqrt(norm);
  return f;
}

std::array<double, 3> direction(std::mt19937_64& rng) {
  const Eigen::Vector3d d = sh::random_direction(rng);
  return {d[0], d[1], d[2]};
}

std::array<double, 3> times(const Matrix3& m, const std::array<double, 3>& v, bool transposed = false) {
  std::array<double, 3> out{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out[i] += (transposed ? m[3 * j + i] : m[3 * i + j]) * v[j];
  return out;
}

// sum f_i y_i(w), zhf's basis through the runtime's recurrence.
double evaluate(const std::vector<double>& f, int order, const std::array<double, 3>& w) {
  std::vector<double> y(order * order);
  runtime::eval_sh(order, w.data(), y.data());
  double sum = 0;
  for (int i = 0; i < order * order; ++i) sum += f[i] * y[i];
  return sum;
}

// g(w) = f(Q^T w) at random directions.
void expect_transformed(const std::vector<double>& f, const std::vector<double>& g, int order, const Matrix3& q,
                        std::mt19937_64& rng, const std::string& what) {
  for (int k = 0; k < 20; ++k) {
    const auto w = direction(rng);
    ASSERT_NEAR(evaluate(g, order, w), evaluate(f, order, times(q, w, true)), kPointwise) << what << ", order " << order;
  }
}

runtime::Rotator<double> rotator_of(int order) {
  return runtime::Rotator<double>::with(gen::fastest_kernels<double>(order));
}

// All 48 signed permutation matrices.
std::vector<Matrix3> signed_permutations() {
  std::vector<Matrix3> out;
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& p : perms)
    for (int signs = 0; signs < 8; ++signs) {
      Matrix3 m{};
      for (int i = 0; i < 3; ++i) m[3 * i + p[i]] = (signs >> i) & 1 ? -1 : 1;
      out.push_back(m);
    }
  return out;
}

TEST(Orthogonal, TheSixteenZKeepingAxisMapsAreExactSignedPermutations) {
  std::mt19937_64 rng(1);
  for (int order = 2; order <= runtime::kMaxGeneratedOrder; ++order) {
    const auto rotator = rotator_of(order);
    int exact = 0;
    for (const Matrix3& q : signed_permutations()) {
      const std::string what = "axis map " + std::to_string(int(q[0])) + " " + std::to_string(int(q[1])) + " " +
                               std::to_string(int(q[2])) + " / ...";
      const runtime::OrthogonalTransform<double> t(rotator, q.data());
      const bool keeps_z = std::abs(q[8]) == 1;
      ASSERT_EQ(t.exact(), keeps_z) << what << ", order " << order;
      const std::vector<double> f = random_unit(order, rng);
      std::vector<double> g(f.size());
      t.apply(f.data(), g.data());
      expect_transformed(f, g, order, q, rng, what);
      if (!keeps_z) continue;
      ++exact;
      // Bit-exact: every output is an input entry, negated or not, and each input is used once.
      std::vector<int> used(f.size(), 0);
      for (std::size_t i = 0; i < g.size(); ++i) {
        std::size_t j = 0;
        while (j < f.size() && !(g[i] == f[j] || g[i] == -f[j])) ++j;
        ASSERT_LT(j, f.size()) << what << ", order " << order << ", index " << i << " is not an input entry";
        ++used[j];
      }
      for (std::size_t j = 0; j < f.size(); ++j) ASSERT_EQ(used[j], 1) << what << ", order " << order << ", index " << j;
    }
    EXPECT_EQ(exact, 16) << "order " << order;
  }
}

TEST(Orthogonal, ReflectionsAreTheReflectedFunction) {
  std::mt19937_64 rng(2);
  for (int order = 2; order <= runtime::kMaxGeneratedOrder; ++order) {
    const auto rotator = rotator_of(order);
    for (int k = 0; k < 10; ++k) {
      const sh::RotationMatrix r = sh::random_rotation(rng);
      Matrix3 q = sh::to_array(r);
      if (k % 2) {
        for (double& x : q) x = -x;  // a rotation times the inversion
      } else {
        for (int i = 0; i < 3; ++i) q[3 * i + 2] = -q[3 * i + 2];  // a mirror, then a rotation
      }
      ASSERT_TRUE(runtime::validate_rotation(q.data(), kRotationDefect, runtime::Handedness::kEither).ok);
      ASSERT_FALSE(runtime::validate_rotation(q.data()).ok);
      const runtime::OrthogonalTransform<double> t(rotator, q.data());
      ASSERT_TRUE(t.reflection());
      const std::vector<double> f = random_unit(order, rng);
      // One by one, and through the band matrices (prepared for many vectors).
      std::vector<double> g(f.size()), through_matrices(f.size());
      t.apply(f.data(), g.data());
      t.prepare(std::size_t(order) * order).apply(f.data(), through_matrices.data());
      expect_transformed(f, g, order, q, rng, "reflection " + std::to_string(k));
      expect_transformed(f, through_matrices, order, q, rng, "reflection " + std::to_string(k) + ", band matrices");
    }
  }
}

TEST(Orthogonal, EulerAnglesComposeAsStated) {
  const double angles[3] = {0.3, -1.1, 2.4};
  auto about = [](char axis, double angle) {
    const double u[3] = {axis == 'X' ? 1.0 : 0.0, axis == 'Y' ? 1.0 : 0.0, axis == 'Z' ? 1.0 : 0.0};
    return runtime::rotation_about_unit_axis(u, angle);
  };
  for (const char* order : {"XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX", "XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ"}) {
    Matrix3 intrinsic, extrinsic;
    ASSERT_TRUE(runtime::rotation_from_euler(angles, order, false, intrinsic));
    ASSERT_TRUE(runtime::rotation_from_euler(angles, order, true, extrinsic));
    const Matrix3 a = about(order[0], angles[0]), b = about(order[1], angles[1]), c = about(order[2], angles[2]);
    const Matrix3 body = runtime::multiply(runtime::multiply(a, b), c), fixed = runtime::multiply(runtime::multiply(c, b), a);
    // Intrinsic is extrinsic with the axes in reverse order: the same matrix.
    Matrix3 reversed;
    const double back[3] = {angles[2], angles[1], angles[0]};
    const std::string flipped{order[2], order[1], order[0]};
    ASSERT_TRUE(runtime::rotation_from_euler(back, flipped, true, reversed));
    for (int i = 0; i < 9; ++i) {
      EXPECT_NEAR(intrinsic[i], body[i], kExactToRounding * 4) << order << " intrinsic, entry " << i;
      EXPECT_NEAR(extrinsic[i], fixed[i], kExactToRounding * 4) << order << " extrinsic, entry " << i;
      EXPECT_NEAR(intrinsic[i], reversed[i], kExactToRounding * 4) << order << " intrinsic vs reversed extrinsic, entry " << i;
    }
  }
  const Matrix3 zyz = runtime::rotation_from_zyz(angles[0], angles[1], angles[2]);
  Matrix3 euler;
  ASSERT_TRUE(runtime::rotation_from_euler(angles, "ZYZ", false, euler));
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(euler[i], zyz[i], kExactToRounding * 4) << "entry " << i;
  Matrix3 untouched{};
  for (const char* bad : {"XXY", "XY", "XYZW", "ABC", "xyz"}) EXPECT_FALSE(runtime::rotation_from_euler(angles, bad, false, untouched)) << bad;
  const double nan_angles[3] = {0, NAN, 0};
  EXPECT_FALSE(runtime::rotation_from_euler(nan_angles, "XYZ", false, untouched));
  EXPECT_EQ(untouched, Matrix3{});
}

using Basis = std::function<std::vector<double>(double x, double y, double z)>;

// The textbook real SH with the Condon-Shortley phase: (-1)^m times the phase-free ones.
std::vector<double> condon_shortley_basis(double x, double y, double z) {
  std::vector<double> b = test::zhf_polynomials(x, y, z);
  for (int l = 0; l < 4; ++l)
    for (int m = -l; m <= l; ++m)
      if (m % 2) b[runtime::index(l, m)] = -b[runtime::index(l, m)];
  return b;
}

TEST(Conventions, EveryPresetIsItsSystemsFunctionInZhfsAxes) {
  constexpr int kOrder = 4;
  const auto rotator = rotator_of(kOrder);
  // Each system evaluates its basis formula in its own coordinates u; three.js's
  // SphericalHarmonics3 and Unity use the phase-free polynomials, in axes of their own.
  const std::vector<std::pair<std::string, Basis>> systems = {
      {"zhf", test::zhf_polynomials},
      {"condon-shortley", condon_shortley_basis},
      {"3dgs", test::gaussian_splatting_basis},
      {"y-up-rh", test::zhf_polynomials},
      {"y-up-lh", test::zhf_polynomials},
  };
  ASSERT_EQ(systems.size(), runtime::conventions().size());
  std::mt19937_64 rng(3);
  for (const auto& system : systems) {
    const std::string& name = system.first;
    const auto& basis = system.second;  // a structured binding cannot be captured in C++17
    const runtime::Convention* c = runtime::find_convention(name);
    ASSERT_NE(c, nullptr) << name;
    const Matrix3 to_zhf = c->to_zhf(), from_zhf = c->from_zhf();
    const runtime::OrthogonalTransform<double> to(rotator, to_zhf.data()), from(rotator, from_zhf.data());
    const std::vector<double> coefficients = random_unit(kOrder, rng);
    std::vector<double> in_zhf(coefficients.size()), back(coefficients.size());
    to.apply(coefficients.data(), in_zhf.data());
    from.apply(in_zhf.data(), back.data());
    // A rotation written in the system's axes, applied to its coefficients.
    const Matrix3 r = sh::to_array(sh::random_rotation(rng));
    const Matrix3 in_zhf_terms = c->rotation_in_zhf_terms(r);
    std::vector<double> turned(coefficients.size());
    rotator.rotate(in_zhf_terms.data(), coefficients.data(), turned.data());
    auto value = [&](const std::vector<double>& f, const std::array<double, 3>& u) {
      const std::vector<double> b = basis(u[0], u[1], u[2]);
      double sum = 0;
      for (int i = 0; i < kOrder * kOrder; ++i) sum += f[i] * b[i];
      return sum;
    };
    for (int k = 0; k < 30; ++k) {
      const auto u = direction(rng);
      // f_system(u) = f_zhf(P u).
      EXPECT_NEAR(value(coefficients, u), evaluate(in_zhf, kOrder, times(c->frame, u)), kPointwise) << name << ", direction " << k;
      // Rotated in its own terms: g(u) = f(R^T u), with the system's basis on both sides.
      EXPECT_NEAR(value(turned, u), value(coefficients, times(r, u, true)), kPointwise) << name << ", rotated, direction " << k;
    }
    for (int i = 0; i < kOrder * kOrder; ++i) EXPECT_NEAR(back[i], coefficients[i], kDouble) << name << ", round trip, index " << i;
    // Sign patterns without a frame change are exact maps.
    EXPECT_EQ(to.exact(), c->frame == runtime::kIdentity) << name;
  }
  EXPECT_EQ(runtime::find_convention("Y-UP"), nullptr);
}

}  // namespace
}  // namespace zhf
