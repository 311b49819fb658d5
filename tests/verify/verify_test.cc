#include <filesystem>
#include <map>
#include <regex>

#include <gtest/gtest.h>

#include "test_support.h"
#include "zhf/codegen/generate.h"
#include "zhf/verify/verify.h"

namespace zhf::verify {
namespace {

namespace fs = std::filesystem;
using codegen::Language;
const fs::path kGenerated = test::source_path("generated");

bool have_vulkan(std::string& why) { return vulkan_available(why); }

VerifyOptions options_for(const fs::path& tree) {
  VerifyOptions options;
  options.generated_dir = tree.string();
  options.runtime_include = test::source_path("runtime/include");
  options.naga_wasm = test::source_path("tools/node/node_modules/naga-wasm");
  options.browser_scripts = test::source_path("web/browser");
  return options;
}

// A tree like generated/ holding order 3 only, made in dir.
void make_tree_of_order3(const fs::path& dir) {
  codegen::GenerateOptions options;
  options.tables_dir = (kGenerated / "lobes").string();
  options.out_dir = (dir / "tree").string();
  options.orders = {3};
  codegen::generate(options);
}

// Scales the first constant of four or more decimals inside rotate_order3 by 1.01: an entry of X_2 or
// A_2, never a unit, a zero or a threshold that a random rotation might not reach.
void corrupt_rotation_constant(const fs::path& file) {
  std::string text = test::read_text(file.string());
  size_t body = text.find("void rotate_order3(");
  if (body == std::string::npos) body = text.find("fn rotate_order3(");
  ASSERT_NE(body, std::string::npos) << file;
  std::smatch m;
  const std::string tail = text.substr(body);
  ASSERT_TRUE(std::regex_search(tail, m, std::regex(R"((0\.[0-9]{4,}))"))) << file;
  const double value = std::stod(m[1]);
  text.replace(body + m.position(1), m.length(1), std::to_string(value * 1.01));
  test::write_text(file.string(), text);
}

TEST(Verify, CheckedInOrder3PassesInEveryLanguage) {
  std::string why;
  VerifyOptions options = options_for(kGenerated);
  options.orders = {3};
  options.rotations = 100;
  if (!have_vulkan(why)) {
    options.languages = {Language::kCpp};
    std::cout << "[ SKIPPED  ] GLSL and HLSL parts: " << why << "\n";
  }
  const VerifyReport report = run_verify(options);
  EXPECT_TRUE(report.pass()) << report.table();
  EXPECT_GE(report.results.size(), options.languages.size() * 6) << report.table();
}

// The C++ files run on several threads at once; the report is the same as on one, an order the
// manifest lacks in its place among them.
TEST(Verify, TheReportIsTheSameOnAnyThreadCount) {
  VerifyOptions options = options_for(kGenerated);
  options.orders = {2, 3, 12, 4};  // no order 12 in generated/
  options.languages = {Language::kCpp};
  options.rotations = 20;
  options.threads = 1;
  const nlohmann::ordered_json one = run_verify(options).to_json();
  options.threads = 3;
  const nlohmann::ordered_json three = run_verify(options).to_json();
  EXPECT_EQ(one.dump(), three.dump());
  ASSERT_EQ(one["errors"].size(), 1u) << one.dump();
  EXPECT_NE(one["errors"][0].get<std::string>().find("order 12: not in"), std::string::npos) << one.dump();
  EXPECT_GE(one["results"].size(), 3u * 6) << one.dump();
}

class VerifyCorruption : public ::testing::TestWithParam<std::string> {};

// "webgpu" is WGSL in headless Chromium's WebGPU (scripts/setup_web.sh installs it; the test
// command sets ZHF_REQUIRE_BROWSER=1, where its absence fails instead of skipping).
TEST_P(VerifyCorruption, OneWrongCoefficientFailsAndIsNamed) {
  const std::string language = GetParam();
  const bool browser = language == "webgpu";
  std::string why;
  if (browser && !test::browser_available(why)) {
    if (test::browser_required()) FAIL() << "ZHF_REQUIRE_BROWSER=1: " << why;
    GTEST_SKIP() << why;
  }
  if (language != "cpp" && !browser && !have_vulkan(why)) GTEST_SKIP() << "no Vulkan device: " << why;
  const test::TempDir dir;
  make_tree_of_order3(dir);
  const std::map<std::string, std::string> files = {{"cpp", "cpp/zhf_order3.h"},
                                                     {"glsl", "glsl/zhf_order3.glsl"},
                                                     {"hlsl", "hlsl/zhf_order3.hlsli"},
                                                     {"wgsl", "wgsl/zhf_order3.wgsl"},
                                                     {"webgpu", "wgsl/zhf_order3.wgsl"}};
  const std::string file = files.at(language);
  corrupt_rotation_constant(dir / "tree" / file);
  VerifyOptions options = options_for(dir / "tree");
  options.orders = {3};
  Language parsed = Language::kWgsl;
  if (!browser) codegen::parse_language(language, parsed);
  options.languages = {parsed};
  if (browser) options.wgsl_on = {WgslDevice::kWebGpu};
  options.rotations = 50;
  const VerifyReport report = run_verify(options);
  EXPECT_FALSE(report.pass());
  bool named = false;
  for (const FunctionResult& r : report.results)
    if (!r.pass && r.function == "rotate_order3" && r.language == language) named = true;
  EXPECT_TRUE(named) << report.table();
  EXPECT_NE(report.table().find("FAIL: order 3, " + language), std::string::npos) << report.table();
}

INSTANTIATE_TEST_SUITE_P(EachLanguage, VerifyCorruption, ::testing::Values("cpp", "glsl", "hlsl", "wgsl", "webgpu"));

TEST(VerifyCli, BadOrdersGetOneLine) {
  const test::RunResult r = test::run_zhf("verify --orders 11..13");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--orders: must be 2..12 (got '13')"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace zhf::verify
