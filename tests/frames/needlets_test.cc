// Needlets (frames/needlets.h): the window against closed forms and a second quadrature; the frame
// against SH evaluation, sampled analysis and the reference rotation.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "test_tolerances.h"

#include "zhf/frames/limits.h"
#include "zhf/frames/needlets.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/rotation_matrix.h"

namespace zhf::frames {
namespace {

using zhf::tolerance::kNeedletFrame;
using zhf::tolerance::kNeedletWindow;

// int_{a}^{b} exp(-1/(1-t^2)) dt by the tanh-sinh rule in long double: a path sharing nothing with
// the adaptive Gauss-Kronrod of the library.
long double tanh_sinh(long double a, long double b) {
  const long double h = 1.0L / 64, half_pi = 1.5707963267948966192313216916397514L;
  long double sum = 0;
  for (int k = -6 * 64; k <= 6 * 64; ++k) {
    const long double s = k * h, u = half_pi * std::sinh(s), c = std::cosh(u);
    const long double x = std::tanh(u), weight = half_pi * std::cosh(s) / (c * c);
    // 1 - t and 1 + t formed without cancellation near the ends.
    const long double one_minus = (b - a) / 2 * (1 - x) + (1 - b), one_plus = (b - a) / 2 * (1 + x) + (1 + a);
    if (one_minus <= 0 || one_plus <= 0) continue;
    sum += weight * std::exp(-1 / (one_minus * one_plus));
  }
  return sum * h * (b - a) / 2;
}

TEST(NeedletWindow, IntegralsMatchAnIndependentQuadrature) {
  EXPECT_NEAR(bump_integral(), 0.4439938162, test::kQuotedTenDigits);  // the value the needlet literature quotes
  EXPECT_NEAR(bump_integral(), double(tanh_sinh(-1, 1)), kNeedletWindow);
  for (double u : {-0.99, -0.7, -0.3, 0.0, 0.2, 0.6, 0.95})
    EXPECT_NEAR(needlet_psi(u), double(tanh_sinh(-1, u) / tanh_sinh(-1, 1)), kNeedletWindow) << "u " << u;
}

// Small weights keep their relative precision: b^2 is one integral of the bump, never the
// difference of two values near 1 (which left 3.53e-8 at B = 2.4, j = 4, l = 14 off by 1 %).
TEST(NeedletWindow, SmallWeightsKeepTheirRelativePrecision) {
  const auto argument = [](double t, double dilation) {  // phi(t) = psi(argument)
    return t <= 1 / dilation ? 1.0 : t > 1 ? -1.0 : 1 - 2 * dilation / (dilation - 1) * (t - 1 / dilation);
  };
  const struct {
    double dilation;
    int j, l;
  } cases[] = {{2.4, 4, 14}, {2.4, 3, 33}, {2.4, 5, 190}, {2.4, 6, 80}, {2.4, 6, 81}, {2.0, 6, 127}, {2.4, 5, 191}};
  for (const auto& c : cases) {
    const double x = c.l / std::pow(c.dilation, c.j);
    const long double reference =
        std::sqrt(tanh_sinh(argument(x, c.dilation), argument(x / c.dilation, c.dilation)) / tanh_sinh(-1, 1));
    ASSERT_GT(reference, 0) << "B " << c.dilation << ", level " << c.j << ", band " << c.l;
    EXPECT_NEAR(needlet_window(x, c.dilation) / double(reference), 1.0, zhf::tolerance::kNeedletWindowRelative)
        << "B " << c.dilation << ", level " << c.j << ", band " << c.l << ": reference " << double(reference);
  }
}

TEST(NeedletWindow, ClosedFormsAndSymmetry) {
  EXPECT_EQ(needlet_psi(-1), 0.0);
  EXPECT_EQ(needlet_psi(1), 1.0);
  EXPECT_NEAR(needlet_psi(0), 0.5, kNeedletWindow);
  for (double u = -1; u <= 1; u += 0.0625) EXPECT_NEAR(needlet_psi(u) + needlet_psi(-u), 1.0, kNeedletWindow) << "u " << u;
  for (double dilation : {1.2, 2.0, 2.4, 3.0}) {
    EXPECT_EQ(needlet_phi(0.5 / dilation, dilation), 1.0);
    EXPECT_EQ(needlet_phi(1.5, dilation), 0.0);
    // Halfway through the fall: psi(0) = 1/2.
    EXPECT_NEAR(needlet_phi((1 + 1 / dilation) / 2, dilation), 0.5, kNeedletWindow) << "B " << dilation;
    EXPECT_EQ(needlet_window(1 / dilation, dilation), 0.0);
    EXPECT_EQ(needlet_window(dilation, dilation), 0.0);
    EXPECT_GT(needlet_window(1.0, dilation), 0.0);
  }
}

TEST(NeedletWindow, PartitionOfUnityForEveryBand) {
  constexpr int kLmax = 2000;
  for (double dilation : {1.2, 1.5, 2.0, 2.4, 3.0, 7.0}) {
    std::vector<double> sum(kLmax + 1, 0.0);
    for (const WindowValue& w : needlet_windows(dilation, kLmax)) {
      ASSERT_GT(w.value, 0.0);
      ASSERT_GT(w.l, std::pow(dilation, w.j - 1) - 1e-9) << "B " << dilation << ", level " << w.j << ", band " << w.l;
      ASSERT_LT(w.l, std::pow(dilation, w.j + 1) + 1e-9) << "B " << dilation << ", level " << w.j << ", band " << w.l;
      sum[w.l] += w.value * w.value;
    }
    EXPECT_EQ(sum[0], 0.0) << "B " << dilation;  // band 0 belongs to the scaling function
    for (int l = 1; l <= kLmax; ++l) ASSERT_NEAR(sum[l], 1.0, kNeedletWindow) << "B " << dilation << ", band " << l;
  }
  EXPECT_THROW(needlet_windows(1.0, 10), std::invalid_argument);
  EXPECT_THROW(needlet_windows(2.0, -1), std::invalid_argument);
  EXPECT_THROW(needlet_windows(2.0, frames::kMaxNeedletBand + 1), std::invalid_argument);
}

// Random SH coefficients of bands 0..L, about unit norm.
std::vector<double> random_sh(int band_limit, std::mt19937_64& rng) {
  sh::Normal<> normal(0, 1.0 / (band_limit + 1));
  std::vector<double> f(runtime::coefficient_count(band_limit + 1));
  for (double& c : f) c = normal(rng);
  return f;
}

double sh_value(const std::vector<double>& f, int band_limit, const Point& x) {
  std::vector<double> y(f.size());
  runtime::eval_sh(band_limit + 1, x.data(), y.data());
  double sum = 0;
  for (std::size_t i = 0; i < f.size(); ++i) sum += f[i] * y[i];
  return sum;
}

double norm2(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return s;
}

std::string designs_folder() { return std::string(ZHF_SOURCE_DIR) + "/generated/designs"; }

struct FrameCase {
  double dilation;
  int band_limit;
  bool designs;
};
const FrameCase kFrameCases[] = {{2.0, 15, true}, {2.0, 12, false}, {1.5, 10, true}, {3.0, 8, false}, {1.2, 9, true}};

NeedletFrame make_frame(const FrameCase& c) {
  if (!c.designs) return NeedletFrame(c.dilation, c.band_limit);
  return NeedletFrame(c.dilation, c.band_limit, [](int degree) { return design_cubature(designs_folder(), degree); });
}

std::string describe(const FrameCase& c) {
  return "B " + std::to_string(c.dilation) + ", L " + std::to_string(c.band_limit) + (c.designs ? ", designs" : ", Gauss");
}

TEST(NeedletFrame, ReconstructsBandLimitedSignalsAndKeepsTheirEnergy) {
  std::mt19937_64 rng(7);
  for (const FrameCase& c : kFrameCases) {
    const NeedletFrame frame = make_frame(c);
    const std::vector<double> f = random_sh(c.band_limit, rng);
    const std::vector<double> beta = frame.analyze(f);
    const std::vector<double> back = frame.synthesize(beta);
    for (std::size_t i = 0; i < f.size(); ++i)
      ASSERT_NEAR(back[i], f[i], kNeedletFrame) << describe(c) << ", band " << runtime::band_of(int(i)) << ", index " << i;
    EXPECT_NEAR(norm2(beta), norm2(f), kNeedletFrame * norm2(f)) << describe(c);  // Parseval: frame bound 1
  }
}

TEST(NeedletFrame, EachBandIsCoveredOnceByTheSquaredWindows) {
  for (const FrameCase& c : kFrameCases) {
    const NeedletFrame frame = make_frame(c);
    std::vector<double> sum(c.band_limit + 1, 0.0);
    for (const NeedletLevel& level : frame.levels()) {
      ASSERT_LE(level.lmax, c.band_limit) << describe(c) << ", level " << level.j;
      ASSERT_GE(level.cubature.degree, 2 * level.lmax) << describe(c) << ", level " << level.j;
      for (int l = level.lmin; l <= level.lmax; ++l) sum[l] += level.window[l - level.lmin] * level.window[l - level.lmin];
    }
    for (int l = 0; l <= c.band_limit; ++l) EXPECT_NEAR(sum[l], 1.0, kNeedletWindow) << describe(c) << ", band " << l;
  }
}

// The kernel by the Legendre series against the addition theorem done with zhf's SH evaluation:
// K(x . xi) = sum_l b_l sum_m y_l^m(x) y_l^m(xi).
TEST(NeedletFrame, KernelsMatchTheAdditionTheorem) {
  std::mt19937_64 rng(3);
  const NeedletFrame frame(2.0, 16);
  for (int a = 0; a < static_cast<int>(frame.levels().size()); ++a) {
    const NeedletLevel& level = frame.levels()[a];
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::Vector3d u = sh::random_direction(rng), v = sh::random_direction(rng);
      const Point x{u[0], u[1], u[2]}, xi{v[0], v[1], v[2]};
      std::vector<double> yx(runtime::coefficient_count(level.lmax + 1)), yxi(yx.size());
      runtime::eval_sh(level.lmax + 1, x.data(), yx.data());
      runtime::eval_sh(level.lmax + 1, xi.data(), yxi.data());
      double direct = 0;
      for (int l = level.lmin; l <= level.lmax; ++l)
        for (int m = -l; m <= l; ++m) direct += level.window[l - level.lmin] * yx[runtime::index(l, m)] * yxi[runtime::index(l, m)];
      ASSERT_NEAR(frame.kernel(a, u.dot(v)), direct, kNeedletFrame) << "level " << level.j << ", trial " << trial;
    }
  }
}

TEST(NeedletFrame, SampledAnalysisAndPointEvaluationAgreeWithTheSpectralPath) {
  std::mt19937_64 rng(11);
  const FrameCase c{2.0, 10, true};
  const NeedletFrame frame = make_frame(c);
  const std::vector<double> f = random_sh(c.band_limit, rng);
  const Cubature samples = design_cubature(designs_folder(), 2 * c.band_limit);
  std::vector<double> values;
  for (const Point& p : samples.points) values.push_back(sh_value(f, c.band_limit, p));
  const std::vector<double> from_sh = frame.analyze(f), from_samples = frame.analyze_samples(samples, values);
  for (std::size_t i = 0; i < from_sh.size(); ++i) ASSERT_NEAR(from_samples[i], from_sh[i], kNeedletFrame) << "coefficient " << i;
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Vector3d u = sh::random_direction(rng);
    const Point x{u[0], u[1], u[2]};
    ASSERT_NEAR(frame.evaluate(from_sh, x), sh_value(f, c.band_limit, x), kNeedletFrame) << "trial " << trial;
  }
  EXPECT_THROW(frame.analyze_samples(gauss_product_cubature(2 * c.band_limit - 1), std::vector<double>(1)), std::invalid_argument);
  EXPECT_THROW(frame.analyze(std::vector<double>(3)), std::invalid_argument);
  EXPECT_THROW(NeedletFrame(2.0, frames::kMaxNeedletFrameBand + 1), std::invalid_argument);
}

// Rotation: the exact path against analysing samples of f(R^T x); the tabulated path converging
// to it as the table grows (linear error ~ h^2, quadratic ~ h^3).
TEST(NeedletFrame, RotationExactAndTabulated) {
  std::mt19937_64 rng(5);
  const FrameCase c{2.0, 8, true};
  const NeedletFrame frame = make_frame(c);
  const std::vector<double> f = random_sh(c.band_limit, rng);
  const std::vector<double> beta = frame.analyze(f);
  const Cubature samples = gauss_product_cubature(2 * c.band_limit);
  const sh::RotationMatrix r = sh::random_rotation(rng);
  std::vector<double> values;
  for (const Point& p : samples.points) {
    const Eigen::Vector3d back = r.transpose() * Eigen::Vector3d(p[0], p[1], p[2]);
    values.push_back(sh_value(f, c.band_limit, {back[0], back[1], back[2]}));
  }
  const std::vector<double> expected = frame.analyze_samples(samples, values), exact = frame.rotate_exact(beta, sh::to_array(r));
  for (std::size_t i = 0; i < exact.size(); ++i) ASSERT_NEAR(exact[i], expected[i], kNeedletFrame) << "coefficient " << i;

  auto error = [&](int size, Interpolation how) {
    const std::vector<double> tabulated = TabulatedNeedletRotation(frame, size, how).rotate(beta, sh::to_array(r));
    double worst = 0;
    for (std::size_t i = 0; i < exact.size(); ++i) worst = std::max(worst, std::abs(tabulated[i] - exact[i]));
    return worst;
  };
  for (Interpolation how : {Interpolation::kLinear, Interpolation::kQuadratic}) {
    const double coarse = error(256, how), fine = error(4096, how);
    const double order = how == Interpolation::kLinear ? 2 : 3;
    // 16 times the nodes: the error falls by 16^order, give or take the kernel's shape.
    EXPECT_LT(fine, coarse * std::pow(16.0, -order) * 4) << (how == Interpolation::kLinear ? "linear" : "quadratic");
  }
}

TEST(NeedletTables, NodesAreExactAndQuadraticsReproduced) {
  const UniformTable square([](double t) { return 3 * t * t - t + 0.5; }, 9);
  for (int i = 0; i < 9; ++i) {
    const double t = -1 + 2.0 * i / 8;
    EXPECT_DOUBLE_EQ(square(t, Interpolation::kLinear), 3 * t * t - t + 0.5) << "node " << i;
  }
  for (double t = -1; t <= 1; t += 0.013) EXPECT_NEAR(square(t, Interpolation::kQuadratic), 3 * t * t - t + 0.5, zhf::tolerance::kQuadraticTableExact) << "t " << t;
  EXPECT_THROW(UniformTable([](double) { return 0.0; }, 2), std::invalid_argument);
}

TEST(NeedletLocalisation, UncutKernelsAndCapEnergies) {
  // A frame whose band limit covers level 3's top band has level 3 uncut.
  const NeedletFrame frame(2.0, 15);
  for (int a = 0; a < static_cast<int>(frame.levels().size()); ++a) {
    const NeedletLevel& level = frame.levels()[a];
    if (level.j < 0 || needlet_top_band(2.0, level.j) > 15) continue;
    const std::function<double(double)> uncut = needlet_kernel(2.0, level.j);
    for (double t = -1; t <= 1; t += 0.125) EXPECT_NEAR(uncut(t), frame.kernel(a, t), kNeedletFrame) << "level " << level.j;
  }
  // Cap energies against a plain midpoint rule in theta (a path sharing nothing with Gauss-Legendre).
  for (int lmax : {3, 7, 15}) {
    const auto delta = [&](double t) { return sh_delta_kernel(lmax, t); };
    const double cap = 2 * runtime::kPi / lmax;
    double outside = 0, all = 0;
    constexpr int kSteps = 200000;
    for (int i = 0; i < kSteps; ++i) {
      const double theta = runtime::kPi * (i + 0.5) / kSteps, k = delta(std::cos(theta)), e = k * k * std::sin(theta);
      all += e;
      if (theta > cap) outside += e;
    }
    EXPECT_NEAR(localisation(delta, lmax, cap).outside_energy, outside / all, zhf::tolerance::kCapEnergyMidpoint) << "lmax " << lmax;
    EXPECT_NEAR(localisation(delta, lmax, runtime::kPi).outside_energy, 0.0, kNeedletFrame) << "lmax " << lmax;
    EXPECT_NEAR(delta(1), (lmax + 1) * (lmax + 1) / (4 * runtime::kPi), kNeedletFrame) << "lmax " << lmax;
  }
  EXPECT_THROW(localisation([](double) { return 1.0; }, frames::kMaxProfileBand + 1, 0.1), std::invalid_argument);
  EXPECT_THROW(needlet_top_band(64, 16), std::invalid_argument);  // 64^17 passes any int
  EXPECT_EQ(needlet_top_band(2, 3), 15);
}

// The cut disturbs every SH band, but needlets centred far from it (in their own wavelengths)
// barely: the reason needlets are used on masked skies.
TEST(NeedletLocalisation, AnEquatorialCutStaysNearTheCutInNeedletCoefficients) {
  const NeedletFrame frame(2.0, 31, [](int degree) { return design_cubature(designs_folder(), degree); });
  const MaskExperiment m = mask_experiment(frame, 10 * runtime::kPi / 180, 8);
  for (std::size_t l = 0; l < m.band_error.size(); ++l) EXPECT_GT(m.band_error[l], 0.1) << "band " << l;
  EXPECT_GT(m.sh_ringing, 0.01);
  bool compared = false;
  for (const MaskLevel& level : m.levels)
    if (level.outside > 0) {
      EXPECT_LT(level.outside_error, 0.1 * level.inside_error) << "level " << level.j;
      compared = true;
    }
  EXPECT_TRUE(compared);
}

}  // namespace
}  // namespace zhf::frames
