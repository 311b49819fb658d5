// Scene specs (zhf generate --scene), the zonal fast path and zhf analyze.
#include <cmath>
#include <filesystem>
#include <random>
#include <regex>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "zhf/io/files.h"
#include "zhf/runtime/zonal.h"
#include "zhf/sh/analysis.h"
#include "zhf/sh/eval.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/verify/verify.h"
#include "zhf/verify/vulkan_runner.h"

namespace zhf {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

std::string write_scene(const fs::path& dir, const std::string& json) {
  const std::string path = (dir / "scene.json").string();
  io::write_file_atomically(path, json);
  return path;
}

// Every function definition in an emitted file.
std::vector<std::string> defined_functions(const std::string& text) {
  std::vector<std::string> names;
  const std::regex def(R"(\nvoid ([A-Za-z_0-9]+)\()");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), def); it != std::sregex_iterator(); ++it)
    names.push_back((*it)[1]);
  return names;
}

verify::VerifyReport verify_dir(const fs::path& dir, std::vector<std::string> languages) {
  std::string why;
  if (!verify::VulkanDevice::open(why)) {
    std::cout << "[ SKIPPED  ] GLSL and HLSL parts: no Vulkan device: " << why << "\n";
    languages = {"cpp"};
  }
  verify::VerifyOptions options;
  options.generated_dir = dir.string();
  options.languages = languages;
  options.rotations = 200;
  return verify::run_verify(options);
}

int manifest_multiplies(const fs::path& manifest, const std::string& path, const std::string& function) {
  const nlohmann::json j = io::read_json_file(manifest.string());
  for (const auto& f : j["files"])
    if (f["path"] == path)
      for (const auto& fn : f["functions"])
        if (fn["name"] == function) return fn["multiplies"].get<int>();
  return -1;
}

TEST(Scene, Order3RgbGlslStandardEmitsOnlyThatAndVerifies) {
  const fs::path dir = test::make_temp_dir();
  const std::string scene = write_scene(dir, R"({"format": "zhf-scene-1", "targets": ["glsl"], "precision": "float",
    "signals": [{"name": "lighting", "order": 3, "channels": 3, "variants": ["standard"]}]})");
  const test::RunResult r = test::run_zhf("generate --scene '" + scene + "' --out '" + (dir / "out").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "cpp"));
  EXPECT_FALSE(fs::exists(dir / "out" / "hlsl"));
  EXPECT_FALSE(fs::exists(dir / "out" / "lobes" / "order_4.json"));
  const std::string glsl = io::read_text_file((dir / "out" / "glsl" / "zhf_order3.glsl").string());
  EXPECT_EQ(defined_functions(glsl), std::vector<std::string>{"rotate_rgb_order3"}) << glsl.substr(0, 600);
  const verify::VerifyReport report = verify_dir(dir / "out", {"glsl"});
  EXPECT_TRUE(report.pass()) << report.table();
  fs::remove_all(dir);
}

TEST(Scene, KnownZeroBandsCostLessAndVerify) {
  const fs::path dir = test::make_temp_dir();
  const std::string scene = write_scene(dir, R"({"format": "zhf-scene-1", "targets": ["cpp", "glsl", "hlsl"],
    "signals": [{"name": "even", "order": 5, "variants": ["standard", "signal-tailored", "dense-matrix", "zonal"],
                 "zero_bands": [1, 3]},
                {"name": "rgba", "order": 4, "channels": 4, "variants": ["standard", "signal-tailored", "dense-matrix", "zonal"]}]})");
  const test::RunResult r = test::run_zhf("generate --scene '" + scene + "' --out '" + (dir / "out").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path checked_in = fs::path(ZHF_SOURCE_DIR) / "generated" / "manifest.json";
  for (const std::string f : {"rotate_order5", "rotate_signal_tailored_order5"}) {
    const int full = manifest_multiplies(checked_in, "cpp/zhf_order5.h", f);
    const int sparse = manifest_multiplies(dir / "out" / "manifest.json", "cpp/zhf_order5.h", f);
    ASSERT_GT(full, 0) << f;
    ASSERT_GT(sparse, 0) << f;
    EXPECT_LT(sparse, full) << f << ": bands 1 and 3 known zero";
  }
  const verify::VerifyReport report = verify_dir(dir / "out", {"cpp", "glsl", "hlsl"});
  EXPECT_TRUE(report.pass()) << report.table();
  // rotate, tailored, dense, zonal per order, per language run (C++ float and double).
  EXPECT_GE(report.results.size(), 2u * 4u * 2u) << report.table();
  fs::remove_all(dir);
}

std::string lobe_stage(const fs::path& manifest, const std::string& path) {
  const nlohmann::json j = io::read_json_file(manifest.string());
  for (const auto& f : j["files"])
    if (f["path"] == path) return f.value("lobe_stage", "");
  return "";
}

// auto puts order 7's lobe stage in double (its float error model is 1.3e-5) and meets 1e-6 in
// every language; float keeps shaders free of double and is held to the model instead.
TEST(Scene, LobePrecisionSaysWhereTheLobeStageRuns) {
  double worst_condition = 0;
  const nlohmann::json table = io::read_json_file(std::string(ZHF_SOURCE_DIR) + "/generated/lobes/order_7.json");
  for (const auto& band : table["bands"])
    worst_condition = std::max(worst_condition, band["condition"].get<double>());
  for (const std::string precision : {"auto", "float"}) {
    const fs::path dir = test::make_temp_dir();
    const std::string scene = write_scene(dir, R"({"format": "zhf-scene-1", "targets": ["cpp", "glsl"], "lobe_precision": ")" +
                                                   precision + R"(", "signals": [{"order": 7, "variants": ["standard"]}]})");
    const test::RunResult r = test::run_zhf("generate --scene '" + scene + "' --out '" + (dir / "out").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const bool wide = precision == "auto";
    const std::string glsl = io::read_text_file((dir / "out" / "glsl" / "zhf_order7.glsl").string());
    EXPECT_EQ(glsl.find("double") != std::string::npos, wide) << precision;
    EXPECT_EQ(lobe_stage(dir / "out" / "manifest.json", "glsl/zhf_order7.glsl"), wide ? "double" : "native") << precision;
    const verify::VerifyReport report = verify_dir(dir / "out", {"cpp", "glsl"});
    EXPECT_TRUE(report.pass()) << report.table();
    for (const verify::FunctionResult& f : report.results)
      if (f.function == "rotate_order7" && f.precision == "float") {
        if (wide) {
          EXPECT_LE(f.max_error, verify::kFloatRotationTolerance) << f.language;
        }
        EXPECT_EQ(f.tolerance, wide ? verify::kFloatRotationTolerance : verify::float_rotation_tolerance(7, worst_condition, false))
            << f.language << " " << precision;
      }
    fs::remove_all(dir);
  }
}

TEST(Scene, BadSpecsGetOneLineNamingTheField) {
  const fs::path dir = test::make_temp_dir();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"format": "zhf-scene-2", "targets": ["glsl"], "signals": []})", "format: 'zhf-scene-2' is not zhf-scene-1"},
      {R"({"format": "zhf-scene-1", "targets": ["metal"], "signals": []})", "targets[0]: 'metal' is not one of"},
      {R"({"format": "zhf-scene-1", "targets": ["glsl"], "precision": "half", "signals": [{"order": 3, "variants": ["standard"]}]})",
       "precision: half is not supported yet"},
      {R"({"format": "zhf-scene-1", "targets": ["glsl"], "lobe_precision": "fast", "signals": [{"order": 3, "variants": ["standard"]}]})",
       "lobe_precision: 'fast' is not one of auto, float, double"},
      {R"({"format": "zhf-scene-1", "targets": ["glsl"], "signals": [{"order": 3, "channels": 2, "variants": ["standard"]}]})",
       "signals[0].channels: must be 1, 3 or 4 (got 2)"},
      {R"({"format": "zhf-scene-1", "targets": ["glsl"], "signals": [{"order": 13, "variants": ["standard"]}]})",
       "signals[0].order: must be 2..12 (got 13)"},
      {R"({"format": "zhf-scene-1", "targets": ["glsl"], "signals": [{"order": 3, "variants": ["fast"]}]})",
       "signals[0].variants[0]: 'fast' is not one of"},
      {R"({"format": "zhf-scene-1", "targets": ["glsl"], "signals": [{"order": 3, "variants": ["standard"], "zero_bands": [3]}]})",
       "signals[0].zero_bands[0]: must be 0..2 (got 3)"},
      {R"({"format": "zhf-scene-1", "targets": ["glsl"], "signals": [{"order": 3, "variants": ["standard"]},
          {"order": 3, "variants": ["zonal"], "zero_bands": [1]}]})", "signals[1].zero_bands: differ from signal"},
      {R"({"format": "zhf-scene-1", "targets": ["glsl"], "signals": [{"order": 3, "variant": ["standard"]}]})",
       "signals[0].variant: unknown field"},
  };
  for (const auto& [json, message] : cases) {
    const std::string scene = write_scene(dir, json);
    const fs::path out = dir / "out";
    const test::RunResult r = test::run_zhf("generate --scene '" + scene + "' --out '" + out.string() + "'");
    EXPECT_EQ(r.exit_code, 3) << json;
    EXPECT_NE(r.err.find(scene + ": " + message), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(out)) << json;
  }
  // A failure after the output directory was made (here: no tables) removes it again.
  const fs::path fresh = dir / "fresh";
  const test::RunResult no_tables = test::run_zhf("generate --tables '" + (dir / "nowhere").string() + "' --out '" + fresh.string() + "'");
  EXPECT_EQ(no_tables.exit_code, 3) << no_tables.err;
  EXPECT_FALSE(fs::exists(fresh));
  const test::RunResult no_out = test::run_zhf("generate --scene '" + write_scene(dir, "{}") + "'");
  EXPECT_EQ(no_out.exit_code, 2);
  EXPECT_NE(no_out.err.find("--out: is required with --scene"), std::string::npos) << no_out.err;
  fs::remove_all(dir);
}

// The zonal fast path against the reference rotation of the same function's full coefficients.
TEST(Zonal, RuntimeFastPathMatchesTheReferenceRotation) {
  std::mt19937_64 rng(8);
  std::normal_distribution<double> normal;
  for (int order : {1, 2, 5, 8, 16}) {
    const runtime::ZonalRotator<double> zonal(order);
    const int n = order * order;
    double worst = 0;
    int worst_index = 0;
    for (int trial = 0; trial < 50; ++trial) {
      const Eigen::Vector3d axis = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
      std::vector<double> weights(order);
      for (double& w : weights) w = normal(rng);
      std::vector<double> f(n), got(n);
      zonal.project(axis.data(), weights.data(), f.data());
      const sh::Matrix3 r = sh::random_rotation(rng);
      const Eigen::VectorXd expected =
          sh::apply_band_matrices(sh::ivanic_ruedenberg(r, order), Eigen::Map<Eigen::VectorXd>(f.data(), n));
      zonal.rotate(r.data(), axis.data(), weights.data(), got.data());
      for (int i = 0; i < n; ++i)
        if (std::abs(got[i] - expected[i]) > worst) worst = std::abs(got[i] - expected[i]), worst_index = i;
    }
    EXPECT_LE(worst, 1e-12) << "order " << order << ", band " << sh::band_of(worst_index) << ", index " << worst_index;
  }
}

// Coefficients of a zonal function about axis with the given y_l^0 weights.
Eigen::VectorXd zonal_coefficients(const Eigen::Vector3d& axis, const std::vector<double>& weights) {
  const int order = static_cast<int>(weights.size());
  Eigen::VectorXd f(order * order);
  sh::eval_sh(order, axis.data(), f.data());
  for (int i = 0; i < f.size(); ++i) f[i] *= std::sqrt(4 * kPi / (2 * sh::band_of(i) + 1)) * weights[sh::band_of(i)];
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
  io::write_file_atomically(in, coeffs_json);
  const test::RunResult r = test::run_zhf("analyze --coeffs '" + in + "' --tolerance " + std::to_string(tolerance) +
                                          " --json '" + out + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return io::read_json_file(out);
}

double axis_error(const nlohmann::json& axis, const Eigen::Vector3d& expected) {
  const Eigen::Vector3d a(axis[0].get<double>(), axis[1].get<double>(), axis[2].get<double>());
  return std::min((a - expected).norm(), (a + expected).norm());
}

TEST(Analyze, BandLimitedSignalWithNoiseBelowToleranceGivesItsOrder) {
  const fs::path dir = test::make_temp_dir();
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  nlohmann::json vectors = nlohmann::json::array();
  for (int v = 0; v < 20; ++v) {
    std::vector<double> f(64);  // order 8 data, signal in bands 0..4, noise 1e-6 above
    for (int i = 0; i < 64; ++i) f[i] = sh::band_of(i) < 5 ? normal(rng) : 1e-6 * normal(rng);
    vectors.push_back(f);
  }
  const nlohmann::json a = analyze(dir, vectors.dump(), 1e-4);
  EXPECT_EQ(a["order"], 8);
  EXPECT_EQ(a["smallest_order"], 5);
  EXPECT_EQ(a["zonal"], false);
  fs::remove_all(dir);
}

TEST(Analyze, ClampedCosineLobeIsZonalWithItsOrderAndZeroOddBands) {
  const fs::path dir = test::make_temp_dir();
  const Eigen::Vector3d axis = Eigen::Vector3d(0.2, -0.7, 0.4).normalized();
  const std::vector<double> w = clamped_cosine_weights(8);
  EXPECT_NEAR(w[0], std::sqrt(kPi) / 2, 1e-14);
  EXPECT_NEAR(w[1], std::sqrt(kPi / 3), 1e-14);
  EXPECT_NEAR(w[3], 0.0, 1e-14);
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
  EXPECT_LE(axis_error(a["axis"], axis), 1e-9);
  fs::remove_all(dir);
}

TEST(Analyze, RotatedZonalFunctionRevealsItsAxis) {
  const fs::path dir = test::make_temp_dir();
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  std::vector<double> weights(6);
  for (double& x : weights) x = normal(rng);
  // Zonal about +z, then turned by a random rotation: its axis is R e_z.
  const Eigen::VectorXd about_z = zonal_coefficients(Eigen::Vector3d::UnitZ(), weights);
  const sh::Matrix3 r = sh::random_rotation(rng);
  const Eigen::VectorXd f = sh::apply_band_matrices(sh::ivanic_ruedenberg(r, 6), about_z);
  const nlohmann::json a = analyze(dir, nlohmann::json::array({std::vector<double>(f.data(), f.data() + f.size())}).dump(), 1e-6);
  EXPECT_EQ(a["zonal"], true);
  EXPECT_LE(axis_error(a["axis"], r.col(2)), 1e-9);
  EXPECT_EQ(a["smallest_order"], 6);
  // A generic (non-zonal) signal is not called zonal.
  Eigen::VectorXd g(36);
  for (int i = 0; i < 36; ++i) g[i] = normal(rng);
  const nlohmann::json b = analyze(dir, nlohmann::json::array({std::vector<double>(g.data(), g.data() + g.size())}).dump(), 1e-6);
  EXPECT_EQ(b["zonal"], false);
  fs::remove_all(dir);
}

TEST(Analyze, EvenOnlyDataIsBandSparseAndWritesAScene) {
  const fs::path dir = test::make_temp_dir();
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  std::string text = "# even bands only, 3 channels per line\n";
  for (int v = 0; v < 4; ++v) {
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < 25; ++i) text += std::to_string(sh::band_of(i) % 2 == 0 ? normal(rng) : 0.0) + " ";
    text += "\n";
  }
  const std::string in = (dir / "coeffs.txt").string(), scene = (dir / "scene.json").string();
  io::write_file_atomically(in, text);
  const test::RunResult r = test::run_zhf("analyze --coeffs '" + in + "' --channels 3 --scene-out '" + scene + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("band-sparse: bands 1 3 can be treated as zero"), std::string::npos) << r.out;
  const nlohmann::json s = io::read_json_file(scene);
  EXPECT_EQ(s["signals"][0]["order"], 5);
  EXPECT_EQ(s["signals"][0]["channels"], 3);
  EXPECT_EQ(s["signals"][0]["zero_bands"], nlohmann::json::array({1, 3}));
  // The scene it wrote is one zhf generate accepts.
  const test::RunResult g = test::run_zhf("generate --scene '" + scene + "' --out '" + (dir / "out").string() + "'");
  EXPECT_EQ(g.exit_code, 0) << g.err;
  fs::remove_all(dir);
}

TEST(Analyze, BadCoefficientFilesGetOneLine) {
  const fs::path dir = test::make_temp_dir();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "file is empty"},
      {"[[1, 2, 3]]", "vector 0: 3 coefficients per channel is not N^2"},
      {"[[1, 0, 0, 0], [1, 0]]", "vector 1: 2 coefficients per channel is not N^2"},
      {"[[1, 0, 0, \"a\"]]", "vector 0, entry 3: not a number"},
      {"1 0 0 0\n1 0 0 nan\n", "line 2: 'nan' is not finite"},
      {"1 0 0 0\n1 0 x 0\n", "line 2: 'x' is not a number"},
      {"[[1, 0, 0, 0]", "not valid JSON"},
      {"{\"a\": 1}", "must be an array of coefficient vectors"},
      {"[[0.5e3333333333, 0, 0, 0]]", "not valid JSON: number overflow"},  // found by fuzz_coefficients
  };
  for (const auto& [content, message] : cases) {
    const std::string in = (dir / "c.txt").string();
    io::write_file_atomically(in, content);
    const test::RunResult r = test::run_zhf("analyze --coeffs '" + in + "'");
    EXPECT_EQ(r.exit_code, 3) << content;
    EXPECT_NE(r.err.find(in + ": " + message), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace zhf
