#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/product.h"
#include "zhf/runtime/table_io.h"
#include "zhf/runtime/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"

// Every product mix of runtime/product.h against direct numerical integration of the product of
// the reconstructed functions. A ZHF-form term is reconstructed independently of Y: as its zonal
// lobes, z_d (2l+1)/(4 pi) P_l((R w_d) . w) (the addition theorem), bands 0 and 1 as SH at R^T w.
namespace zhf::runtime {
namespace {

using tolerance::kProductAgainstIntegration;

double legendre(int l, double x) {
  double p0 = 1, p1 = x;
  if (l == 0) return p0;
  for (int k = 2; k <= l; ++k) {
    const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  return p1;
}

// A term as the integrator sees it: SH coefficients, or z over a table's lobes rotated by r.
struct Term {
  std::vector<double> values;
  const LobeTable* table = nullptr;  // null: SH
  Matrix3 r = kIdentity;
  ZhfBasis basis() const { return ZhfBasis(*table, r.data()); }
};

double evaluate(const Term& t, int order, const double w[3]) {
  std::vector<double> y(order * order);
  if (!t.table) {
    eval_sh(order, w, y.data());
    double sum = 0;
    for (int i = 0; i < order * order; ++i) sum += y[i] * t.values[i];
    return sum;
  }
  const Matrix3& r = t.r;
  const double back[3] = {r[0] * w[0] + r[3] * w[1] + r[6] * w[2], r[1] * w[0] + r[4] * w[1] + r[7] * w[2],
                          r[2] * w[0] + r[5] * w[1] + r[8] * w[2]};  // R^T w
  eval_sh(std::min(order, 2), back, y.data());
  double sum = 0;
  for (int i = 0; i < std::min(order, 2) * std::min(order, 2); ++i) sum += y[i] * t.values[i];
  for (const TableBand& band : t.table->bands)
    for (int d = 0; d < 2 * band.l + 1; ++d) {
      const auto& u = t.table->lobes[band.lobes[d]].xyz;
      const double cosine = (r[0] * u[0] + r[1] * u[1] + r[2] * u[2]) * w[0] + (r[3] * u[0] + r[4] * u[1] + r[5] * u[2]) * w[1] +
                            (r[6] * u[0] + r[7] * u[1] + r[8] * u[2]) * w[2];
      sum += t.values[band.l * band.l + d] * (2 * band.l + 1) / (4 * kPi) * legendre(band.l, cosine);
    }
  return sum;
}

// Gauss-Legendre in z x uniform phi, exact for SH products of total degree 3(order-1).
template <class F>
double integrate(int order, F&& integrand) {
  const int degree = 3 * (order - 1), nz = degree / 2 + 1, nphi = degree + 1;
  std::vector<double> nodes, weights;
  sh::gauss_legendre(nz, nodes, weights);
  double sum = 0;
  for (int i = 0; i < nz; ++i)
    for (int j = 0; j < nphi; ++j) {
      const double s = std::sqrt(1 - nodes[i] * nodes[i]), phi = 2 * kPi * j / nphi;
      const double w[3] = {s * std::cos(phi), s * std::sin(phi), nodes[i]};
      sum += weights[i] * 2 * kPi / nphi * integrand(w);
    }
  return sum;
}

class ProductMixes : public ::testing::TestWithParam<int> {
 protected:
  void SetUp() override {
    order_ = GetParam();
    table_ = order_ == 2 ? lobe_free_table() : read_lobe_table(test::checked_in_table(order_));
  }
  Term random_term(std::mt19937_64& rng, bool zhf, bool rotated) const {
    sh::Normal<> normal;
    Term t;
    for (int i = 0; i < order_ * order_; ++i) t.values.push_back(normal(rng) / order_);
    if (zhf) t.table = &table_;
    if (rotated) {
      const sh::RotationMatrix r = sh::random_rotation(rng);
      for (int i = 0; i < 9; ++i) t.r[i] = r(i / 3, i % 3);
    }
    return t;
  }
  int order_ = 0;
  LobeTable table_;
};

// Every mix: each of f, g, h in SH, in ZHF form, or in rotated ZHF form.
TEST_P(ProductMixes, DoubleAndTripleProductsMatchIntegration) {
  const int n = order_ * order_;
  const ShProduct product(order_);
  std::mt19937_64 rng(100 + order_);
  for (int mix = 0; mix < 27; ++mix) {
    const int kinds[3] = {mix % 3, mix / 3 % 3, mix / 9};  // 0 SH, 1 ZHF, 2 rotated ZHF
    Term terms[3];
    for (int k = 0; k < 3; ++k) terms[k] = random_term(rng, kinds[k] > 0, kinds[k] == 2);
    std::vector<ZhfBasis> bases;
    bases.reserve(3);
    ProductTerm<double> p[3];
    for (int k = 0; k < 3; ++k) {
      p[k].values = terms[k].values.data();
      if (terms[k].table) {
        bases.push_back(terms[k].basis());
        p[k].basis = &bases.back();
      }
    }
    const std::string where = "order " + std::to_string(order_) + ", mix " + std::to_string(kinds[0]) + std::to_string(kinds[1]) +
                              std::to_string(kinds[2]) + " (0 SH, 1 ZHF, 2 rotated ZHF)";
    const double triple = integrate(order_, [&](const double* w) {
      return evaluate(terms[0], order_, w) * evaluate(terms[1], order_, w) * evaluate(terms[2], order_, w);
    });
    EXPECT_NEAR(triple_product(product, p[0], p[1], p[2]), triple, kProductAgainstIntegration) << where;
    // The same in float.
    std::vector<float> single[3];
    ProductTerm<float> pf[3];
    for (int k = 0; k < 3; ++k) {
      single[k].assign(terms[k].values.begin(), terms[k].values.end());
      pf[k] = {single[k].data(), p[k].basis};
    }
    EXPECT_NEAR(triple_product(product, pf[0], pf[1], pf[2]), triple, tolerance::kFloatProduct) << where << ", float";
    if (order_ <= runtime::kMaxTripleCouplingOrder) {
      const ZhfBasis* slots[3] = {p[0].basis, p[1].basis, p[2].basis};
      const std::vector<double> t = triple_coupling(order_, slots);
      double contracted = 0;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          for (int k = 0; k < n; ++k) contracted += t[(size_t(i) * n + j) * n + k] * p[0].values[i] * p[1].values[j] * p[2].values[k];
      EXPECT_NEAR(contracted, triple, kProductAgainstIntegration) << where << ", stored coupling tensor";
    }
    if (mix < 9) {  // the double products of f and g
      const double expected = integrate(order_, [&](const double* w) { return evaluate(terms[0], order_, w) * evaluate(terms[1], order_, w); });
      EXPECT_NEAR(double_product(order_, p[0], p[1]), expected, kProductAgainstIntegration) << where << ", double product";
      EXPECT_NEAR(double_product(order_, pf[0], pf[1]), expected, tolerance::kFloatProduct) << where << ", double product in float";
      const Matrix c = double_coupling(order_, p[0].basis, p[1].basis);
      double coupled = 0;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) coupled += p[0].values[i] * c(i, j) * p[1].values[j];
      EXPECT_NEAR(coupled, expected, kProductAgainstIntegration) << where << ", double coupling matrix";
    }
  }
}

TEST_P(ProductMixes, ProjectedProductAndSquareMatchIntegration) {
  const int n = order_ * order_;
  const ShProduct product(order_);
  std::mt19937_64 rng(200 + order_);
  const Term f = random_term(rng, false, false), g = random_term(rng, false, false);
  std::vector<double> h(n), sq(n);
  std::vector<float> hf(n), ff(f.values.begin(), f.values.end()), gf(g.values.begin(), g.values.end());
  product.product(f.values.data(), g.values.data(), h.data());
  product.product(ff.data(), gf.data(), hf.data());
  product.square(f.values.data(), sq.data());
  for (int c = 0; c < n; ++c) {
    std::vector<double> y(n);
    auto basis_c = [&](const double* w) {
      eval_sh(order_, w, y.data());
      return y[c];
    };
    const double fg = integrate(order_, [&](const double* w) { return evaluate(f, order_, w) * evaluate(g, order_, w) * basis_c(w); });
    const double ff2 = integrate(order_, [&](const double* w) { return std::pow(evaluate(f, order_, w), 2) * basis_c(w); });
    const int l = band_of(c);
    EXPECT_NEAR(h[c], fg, kProductAgainstIntegration) << "order " << order_ << ", band " << l << ", index " << c;
    EXPECT_NEAR(hf[c], fg, tolerance::kFloatProduct) << "float, order " << order_ << ", band " << l << ", index " << c;
    EXPECT_NEAR(sq[c], ff2, kProductAgainstIntegration) << "square, order " << order_ << ", band " << l << ", index " << c;
  }
}

INSTANTIATE_TEST_SUITE_P(Orders, ProductMixes, ::testing::Values(2, 3, 5, 8, 12));

TEST(ProductTable, NonzeroCountsMatchSnyder2006) {
  // Snyder's table of non-zero real Gaunt coefficients applied naively (ordered pairs), orders 3..7.
  const int expected[] = {83, 353, 1158, 2907, 6460};
  for (int order = 3; order <= 7; ++order) {
    int ordered = 0;
    const ShProduct product(order);
    for (const GauntEntry& e : product.table()) ordered += e.a == e.b ? 1 : 2;
    EXPECT_EQ(ordered, expected[order - 3]) << "order " << order;
  }
}

TEST(ProductTable, RefusesCouplingTensorsBeyondItsOrderAndBasesOfAnotherOrder) {
  const ZhfBasis* slots[3] = {nullptr, nullptr, nullptr};
  EXPECT_THROW(triple_coupling(runtime::kMaxTripleCouplingOrder + 1, slots), std::invalid_argument);
  const ZhfBasis basis(read_lobe_table(test::source_path("generated/lobes/order_4.json")));
  const ZhfBasis* wrong[3] = {&basis, nullptr, nullptr};
  EXPECT_THROW(triple_coupling(5, wrong), std::invalid_argument);
  EXPECT_THROW(double_coupling(3, &basis, nullptr), std::invalid_argument);
  const std::vector<double> x(25, 0.1);
  EXPECT_THROW(double_product<double>(5, {x.data(), &basis}, {x.data(), nullptr}), std::invalid_argument);
}

}  // namespace
}  // namespace zhf::runtime
