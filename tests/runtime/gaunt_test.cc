#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "zhf/runtime/gaunt.h"
#include "zhf/runtime/limits.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/slow_reference.h"
#include "test_tolerances.h"

// Gaunt coefficients (runtime/gaunt.h, Wigner 3j closed form) against an independent path: a
// product quadrature (Gauss-Legendre in z x uniform phi, exact for degree 3(N-1)) of the slow
// long-double SH of sh/.
namespace zhf::runtime {
namespace {

using tolerance::kGauntAgainstQuadrature;

// y_a at every node of a quadrature exact for degree 3(order-1), in long double, with weights.
struct Quadrature {
  int n = 0;
  std::vector<long double> weight;
  std::vector<std::vector<long double>> y;  // y[a][node]

  explicit Quadrature(int order) : n(order * order), y(order * order) {
    const int degree = 3 * (order - 1), nz = degree / 2 + 1, nphi = degree + 1;
    std::vector<double> nodes, weights;
    sh::gauss_legendre(nz, nodes, weights);
    for (int i = 0; i < nz; ++i)
      for (int j = 0; j < nphi; ++j) {
        const long double theta = std::acos(static_cast<long double>(nodes[i]));
        const long double phi = 2 * M_PIl * j / nphi;
        weight.push_back(weights[i] * 2 * M_PIl / nphi);
        for (int l = 0; l < order; ++l)
          for (int m = -l; m <= l; ++m) y[index(l, m)].push_back(sh::slow::real_sh(l, m, theta, phi, false));
      }
  }
  long double integral(int a, int b, int c) const {
    long double sum = 0;
    for (size_t k = 0; k < weight.size(); ++k) sum += weight[k] * y[a][k] * y[b][k] * y[c][k];
    return sum;
  }
};

TEST(Gaunt, EveryTripleUpToOrder8MatchesQuadrature) {
  constexpr int kOrder = 8;
  const Quadrature q(kOrder);
  for (int a = 0; a < q.n; ++a)
    for (int b = a; b < q.n; ++b)
      for (int c = b; c < q.n; ++c) {
        const double expected = static_cast<double>(q.integral(a, b, c));
        ASSERT_NEAR(real_gaunt(a, b, c), expected, kGauntAgainstQuadrature) << "order 8, indices " << a << " " << b << " " << c;
      }
}

TEST(Gaunt, Order16TableMatchesQuadratureAndIsComplete) {
  constexpr int kOrder = runtime::kMaxGauntOrder;
  const std::vector<GauntEntry> table = gaunt_table(kOrder);
  const Quadrature q(kOrder);
  for (const GauntEntry& e : table)
    ASSERT_NEAR(e.value, static_cast<double>(q.integral(e.a, e.b, e.c)), kGauntAgainstQuadrature)
        << "order 16, indices " << e.a << " " << e.b << " " << e.c;
  // Random triples the table leaves out are zero by quadrature too.
  std::mt19937_64 rng(16);
  auto pick = [&](std::mt19937_64& g) { return sh::uniform_index(g, q.n); };
  for (int k = 0; k < 20000; ++k) {
    const int a = pick(rng), b = pick(rng), c = pick(rng);
    if (gaunt_allowed(band_of(a), a - band_of(a) * (band_of(a) + 1), band_of(b), b - band_of(b) * (band_of(b) + 1), band_of(c),
                      c - band_of(c) * (band_of(c) + 1)))
      continue;
    ASSERT_NEAR(static_cast<double>(q.integral(a, b, c)), 0.0, kGauntAgainstQuadrature) << "indices " << a << " " << b << " " << c;
  }
}

TEST(Gaunt, SymmetricAndBandZeroIsTheIdentity) {
  constexpr int kN = 36;
  for (int a = 0; a < kN; ++a)
    for (int b = 0; b < kN; ++b) {
      EXPECT_NEAR(real_gaunt(0, a, b), a == b ? kInvSqrt4Pi : 0.0, zhf::tolerance::kGauntSymmetry) << "indices 0 " << a << " " << b;
      for (int c = 0; c < kN; ++c) {
        const double g = real_gaunt(a, b, c);
        ASSERT_EQ(g, real_gaunt(b, a, c)) << a << " " << b << " " << c;
        ASSERT_NEAR(g, real_gaunt(c, b, a), zhf::tolerance::kGauntSymmetry) << a << " " << b << " " << c;
      }
    }
}

TEST(Gaunt, SelectionRulesHold) {
  // Odd l1 + l2 + l3, broken triangles and odd sine counts are zero whatever the table says.
  EXPECT_EQ(real_gaunt(index(1, 0), index(1, 0), index(1, 0)), 0.0);
  EXPECT_EQ(real_gaunt(index(1, 1), index(1, 1), index(4, 0)), 0.0);
  EXPECT_EQ(real_gaunt(index(2, -1), index(2, 1), index(2, 0)), 0.0);
  EXPECT_GT(std::abs(real_gaunt(index(2, -1), index(2, -1), index(2, 0))), 0.01);
  for (const GauntEntry& e : gaunt_table(6)) {
    ASSERT_LE(e.a, e.b);
    const int lc = band_of(e.c), la = band_of(e.a), lb = band_of(e.b);
    ASSERT_EQ((la + lb + lc) % 2, 0) << e.a << " " << e.b << " " << e.c;
    ASSERT_TRUE(lc >= std::abs(la - lb) && lc <= la + lb) << e.a << " " << e.b << " " << e.c;
  }
}

TEST(Gaunt, RefusesOrdersOutsideItsRange) {
  EXPECT_THROW(gaunt_table(0), std::invalid_argument);
  EXPECT_THROW(gaunt_table(runtime::kMaxGauntOrder + 1), std::invalid_argument);
}

}  // namespace
}  // namespace zhf::runtime
