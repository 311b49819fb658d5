#include <filesystem>
#include <regex>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "zhf/io/files.h"
#include "zhf/verify/verify.h"
#include "zhf/verify/vulkan_runner.h"

namespace zhf::verify {
namespace {

namespace fs = std::filesystem;
const fs::path kGenerated = fs::path(ZHF_SOURCE_DIR) / "generated";

bool have_vulkan(std::string& why) { return VulkanDevice::open(why) != nullptr; }

// A copy of generated/ holding order 3 only.
fs::path copy_order3() {
  const fs::path dir = test::make_temp_dir();
  for (const char* f : {"lobes/order_3.json", "cpp/zhf_order3.h", "glsl/zhf_order3.glsl", "hlsl/zhf_order3.hlsli"}) {
    fs::create_directories((dir / f).parent_path());
    fs::copy_file(kGenerated / f, dir / f);
  }
  return dir;
}

// Scales the first constant inside rotate_order3 by 1.01.
void corrupt_rotation_constant(const fs::path& file) {
  std::string text = io::read_text_file(file.string());
  const size_t body = text.find("void rotate_order3(");
  ASSERT_NE(body, std::string::npos) << file;
  std::smatch m;
  const std::string tail = text.substr(body);
  ASSERT_TRUE(std::regex_search(tail, m, std::regex(R"(([0-9]+\.[0-9]+(e[-+]?[0-9]+)?))"))) << file;
  const double value = std::stod(m[1]);
  text.replace(body + m.position(1), m.length(1), std::to_string(value * 1.01));
  io::write_file_atomically(file.string(), text);
}

TEST(Verify, CheckedInOrder3PassesInEveryLanguage) {
  std::string why;
  VerifyOptions options;
  options.generated_dir = kGenerated.string();
  options.orders = {3};
  options.rotations = 100;
  if (!have_vulkan(why)) {
    options.languages = {"cpp"};
    std::cout << "[ SKIPPED  ] GLSL and HLSL parts: " << why << "\n";
  }
  const VerifyReport report = run_verify(options);
  EXPECT_TRUE(report.pass()) << report.table();
  EXPECT_GE(report.results.size(), options.languages.size() * 6) << report.table();
}

class VerifyCorruption : public ::testing::TestWithParam<std::string> {};

TEST_P(VerifyCorruption, OneWrongCoefficientFailsAndIsNamed) {
  const std::string language = GetParam();
  std::string why;
  if (language != "cpp" && !have_vulkan(why)) GTEST_SKIP() << "no Vulkan device: " << why;
  const fs::path dir = copy_order3();
  const char* file = language == "cpp" ? "cpp/zhf_order3.h" : language == "glsl" ? "glsl/zhf_order3.glsl" : "hlsl/zhf_order3.hlsli";
  corrupt_rotation_constant(dir / file);
  VerifyOptions options;
  options.generated_dir = dir.string();
  options.orders = {3};
  options.languages = {language};
  options.rotations = 50;
  const VerifyReport report = run_verify(options);
  EXPECT_FALSE(report.pass());
  bool named = false;
  for (const FunctionResult& r : report.results)
    if (!r.pass && r.function == "rotate_order3" && r.language == language) named = true;
  EXPECT_TRUE(named) << report.table();
  EXPECT_NE(report.table().find("FAIL: order 3, " + language), std::string::npos) << report.table();
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(EachLanguage, VerifyCorruption, ::testing::Values("cpp", "glsl", "hlsl"));

TEST(VerifyCli, BadOrdersGetOneLine) {
  const test::RunResult r = test::run_zhf("verify --orders 11..13");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--orders: 13 is outside [2, 12]"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace zhf::verify
