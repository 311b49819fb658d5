// zhf analyze end to end: the order data needs, known-zero bands, zonal signals and their axes
// and weights, through the real binary.
#include <cmath>
#include <random>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "test_support.h"
#include "test_tolerances.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"

namespace zhf {
namespace {

namespace fs = std::filesystem;
using runtime::kPi;
constexpr double kAxis = zhf::tolerance::kZonalFit;

// Coefficients of a zonal function about axis with the given y_l^0 weights.
Eigen::VectorXd zonal_coefficients(const Eigen::Vector3d& axis, const std::vector<double>& weights) {
  const int order = static_cast<int>(weights.size());
  Eigen::VectorXd f(order * order);
  runtime::eval_sh(order, axis.data(), f.data());
  for (int i = 0; i < f.size(); ++i) f[i] *= std::sqrt(4 * kPi / (2 * runtime::band_of(i) + 1)) * weights[runtime::band_of(i)];
  return f;
}

// max(cos theta, 0) about +z: zonal[l] = 2 pi int_0^1 t sqrt((2l+1)/(4 pi)) P_l(t) dt, by
// Gauss-Legendre on [0, 1] (exact: the integrand is a polynomial of degree l + 1).
std::vector<double> clamped_cosine_weights(int order) {
  const double nodes[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                           0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
  const double gw[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                        0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  std::vector<double> out(order, 0.0);
  for (int l = 0; l < order; ++l)
    for (int k = 0; k < 8; ++k) {
      const double t = 0.5 * (nodes[k] + 1);
      double p0 = 1, p1 = t;  // P_l(t) by the three-term recurrence
      for (int j = 2; j <= l; ++j) {
        const double p2 = ((2 * j - 1) * t * p1 - (j - 1) * p0) / j;
        p0 = p1;
        p1 = p2;
      }
      const double p = l == 0 ? 1.0 : p1;
      out[l] += 0.5 * gw[k] * 2 * kPi * t * std::sqrt((2 * l + 1) / (4 * kPi)) * p;
    }
  return out;
}

nlohmann::json analyze(const fs::path& dir, const std::string& coeffs_json, double tolerance) {
  const std::string in = (dir / "coeffs.json").string(), out = (dir / "analysis.json").string();
  test::write_text(in, coeffs_json);
  const test::RunResult r = test::run_zhf("analyze --coeffs '" + in + "' --tolerance " + std::to_string(tolerance) +
                                          " --json '" + out + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return test::read_json(out);
}

double axis_error(const nlohmann::json& axis, const Eigen::Vector3d& expected) {
  const Eigen::Vector3d a(axis[0].get<double>(), axis[1].get<double>(), axis[2].get<double>());
  return std::min((a - expected).norm(), (a + expected).norm());
}

TEST(Analyze, BandLimitedSignalWithNoiseBelowToleranceGivesItsOrder) {
  const test::TempDir dir;
  std::mt19937_64 rng(5);
  sh::Normal<> normal;
  nlohmann::json vectors = nlohmann::json::array();
  for (int v = 0; v < 20; ++v) {
    std::vector<double> f(64);  // order 8 data, signal in bands 0..4, noise 1e-6 above
    for (int i = 0; i < 64; ++i) f[i] = runtime::band_of(i) < 5 ? normal(rng) : 1e-6 * normal(rng);
    vectors.push_back(f);
  }
  const nlohmann::json a = analyze(dir, vectors.dump(), 1e-4);
  EXPECT_EQ(a["order"], 8);
  EXPECT_EQ(a["smallest_order"], 5);
  EXPECT_EQ(a["zonal"], false);
}

TEST(Analyze, ClampedCosineLobeIsZonalWithItsOrderAndZeroOddBands) {
  const test::TempDir dir;
  const Eigen::Vector3d axis = Eigen::Vector3d(0.2, -0.7, 0.4).normalized();
  const std::vector<double> w = clamped_cosine_weights(8);
  EXPECT_NEAR(w[0], std::sqrt(kPi) / 2, zhf::tolerance::kSlowPathsAgreement);
  EXPECT_NEAR(w[1], std::sqrt(kPi / 3), zhf::tolerance::kSlowPathsAgreement);
  EXPECT_NEAR(w[3], 0.0, zhf::tolerance::kSlowPathsAgreement);
  const Eigen::VectorXd f = zonal_coefficients(axis, w);
  // The expected order, from the closed-form weights alone (energy of band l is w_l^2).
  const double tolerance = 0.05;
  double total = 0;
  for (double x : w) total += x * x;
  int expected = 8;
  for (int n = 1; n <= 8; ++n) {
    double tail = 0;
    for (int l = n; l < 8; ++l) tail += w[l] * w[l];
    if (tail <= tolerance * tolerance * total) {
      expected = n;
      break;
    }
  }
  const nlohmann::json a = analyze(dir, nlohmann::json::array({std::vector<double>(f.data(), f.data() + f.size())}).dump(), tolerance);
  EXPECT_EQ(a["smallest_order"], expected);
  EXPECT_EQ(a["zonal"], true);
  EXPECT_LE(axis_error(a["axis"], axis), kAxis);
}

TEST(Analyze, RotatedZonalFunctionRevealsItsAxis) {
  const test::TempDir dir;
  std::mt19937_64 rng(11);
  sh::Normal<> normal;
  std::vector<double> weights(6);
  for (double& x : weights) x = normal(rng);
  // Zonal about +z, then turned by a random rotation: its axis is R e_z.
  const Eigen::VectorXd about_z = zonal_coefficients(Eigen::Vector3d::UnitZ(), weights);
  const sh::RotationMatrix r = sh::random_rotation(rng);
  const Eigen::VectorXd f = sh::apply_band_matrices(sh::ivanic_ruedenberg(r, 6), about_z);
  const nlohmann::json a = analyze(dir, nlohmann::json::array({std::vector<double>(f.data(), f.data() + f.size())}).dump(), 1e-6);
  EXPECT_EQ(a["zonal"], true);
  EXPECT_LE(axis_error(a["axis"], r.col(2)), kAxis);
  EXPECT_EQ(a["smallest_order"], 6);
  // The reported weights rebuild the function: f = sqrt(4 pi / (2l+1)) zonal[l] y_l^m(axis).
  const nlohmann::json& fit = a["signals"][0];
  std::vector<double> reported;
  for (const auto& x : fit["weights"]) reported.push_back(x.get<double>());
  ASSERT_EQ(reported.size(), weights.size());
  const Eigen::Vector3d found(fit["axis"][0].get<double>(), fit["axis"][1].get<double>(), fit["axis"][2].get<double>());
  const Eigen::VectorXd rebuilt = zonal_coefficients(found, reported);
  for (int i = 0; i < f.size(); ++i)
    EXPECT_NEAR(rebuilt[i], f[i], kAxis) << "band " << runtime::band_of(i) << ", index " << i;
  // A generic (non-zonal) signal is not called zonal.
  Eigen::VectorXd g(36);
  for (int i = 0; i < 36; ++i) g[i] = normal(rng);
  const nlohmann::json b = analyze(dir, nlohmann::json::array({std::vector<double>(g.data(), g.data() + g.size())}).dump(), 1e-6);
  EXPECT_EQ(b["zonal"], false);
}

TEST(Analyze, EvenOnlyDataIsBandSparseAndWritesAScene) {
  const test::TempDir dir;
  std::mt19937_64 rng(3);
  sh::Normal<> normal;
  std::string text = "# even bands only, 3 channels per line\n";
  for (int v = 0; v < 4; ++v) {
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < 25; ++i) text += std::to_string(runtime::band_of(i) % 2 == 0 ? normal(rng) : 0.0) + " ";
    text += "\n";
  }
  const std::string in = (dir / "coeffs.txt").string(), scene = (dir / "scene.json").string();
  test::write_text(in, text);
  const test::RunResult r = test::run_zhf("analyze --coeffs '" + in + "' --channels 3 --scene-out '" + scene + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("band-sparse: bands 1 3 can be treated as zero"), std::string::npos) << r.out;
  const nlohmann::json s = test::read_json(scene);
  EXPECT_EQ(s["signals"][0]["order"], 5);
  EXPECT_EQ(s["signals"][0]["channels"], 3);
  EXPECT_EQ(s["signals"][0]["zero_bands"], nlohmann::json::array({1, 3}));
  // The scene it wrote is one zhf generate accepts.
  const test::RunResult g = test::run_zhf("generate --scene '" + scene + "' --out '" + (dir / "out").string() + "'");
  EXPECT_EQ(g.exit_code, 0) << g.err;
}

TEST(Analyze, BadCoefficientFilesGetOneLine) {
  const test::TempDir dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "file is empty"},
      {"[[1, 2, 3]]", "vector 0: 3 coefficients per channel is not N^2"},
      {"[[1, 0, 0, 0], [1, 0]]", "vector 1: 2 coefficients per channel is not N^2"},
      {"[[1, 0, 0, \"a\"]]", "[0][3]: expected a number, found a string"},
      {"1 0 0 0\n1 0 0 nan\n", "line 2: 'nan' is not finite"},
      {"1 0 0 0\n1 0 x 0\n", "line 2: 'x' is not a number"},
      {"[[1, 0, 0, 0]", "not valid JSON"},
      {"{\"a\": 1}", "top level: expected an array, found an object"},
      {"[[0.5e3333333333, 0, 0, 0]]", "not valid JSON: the number '0.5e3333333333' is beyond the range of a double"},  // found by fuzz_coefficients
      {"[[1e200, 0, 0, 0]]", "[0][0]: 1e200 is beyond the largest coefficient magnitude, 1e150"},
      {"[[1, 0, 0, 0]] x", "not valid JSON at line 1, column 16: syntax error while parsing value - invalid literal"},
      {"1 0 0 0x1\n", "line 1: '0x1' is not a number"},
  };
  for (const auto& [content, message] : cases) {
    const std::string in = (dir / "c.txt").string();
    test::write_text(in, content);
    const test::RunResult r = test::run_zhf("analyze --coeffs '" + in + "'");
    EXPECT_EQ(r.exit_code, 3) << content;
    EXPECT_NE(r.err.find(in + ": " + message), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

}  // namespace
}  // namespace zhf
