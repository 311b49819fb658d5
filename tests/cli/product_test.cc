// zhf product: SH products of coefficient files, projected to an order.
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/runtime/tolerances.h"
#include "zhf/sh/random.h"

namespace zhf {
namespace {

namespace fs = std::filesystem;
constexpr double kTolerance = runtime::tolerance::kProductAgainstIntegration;
using runtime::kPi;

TEST(ProductCli, ClosedFormsChannelsBroadcastAndOrders) {
  const test::TempDir dir;
  const std::string one = (dir / "one.json").string(), g = (dir / "g.json").string(), z = (dir / "z.json").string();
  const std::string out = (dir / "out.json").string();
  // The function 1 (f_0 = sqrt(4 pi)) times g is g: one vector used with each of g's, per channel.
  std::mt19937_64 rng(5);
  sh::Normal<> normal;
  nlohmann::json vectors = nlohmann::json::array();
  for (int v = 0; v < 3; ++v) {
    nlohmann::json rgb = nlohmann::json::array();
    for (int c = 0; c < 3; ++c) {
      std::vector<double> x(16);
      for (double& e : x) e = normal(rng);
      rgb.push_back(x);
    }
    vectors.push_back(rgb);
  }
  test::write_text(g, vectors.dump());
  const double s = std::sqrt(4 * kPi);
  test::write_text(one, nlohmann::json::array({nlohmann::json::array({{s}, {s}, {s}})}).dump());
  test::RunResult r = test::run_zhf("product --lhs '" + one + "' --rhs '" + g + "' --out '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json got = test::read_json(out);
  ASSERT_EQ(got.size(), 3u);
  for (int v = 0; v < 3; ++v)
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < 16; ++i)
        EXPECT_NEAR(got[v][c][i].get<double>(), vectors[v][c][i].get<double>(), kTolerance) << "vector " << v << ", channel " << c << ", index " << i;

  // y_1^0 squared = (3 / 4 pi) z^2: 1 / sqrt(4 pi) in band 0 and 2 / sqrt(20 pi) at (2, 0); nothing
  // else, at the default order 2 (band 0 only survives besides band 1's zeros) and at order 3.
  test::write_text(z, "0 0 1 0\n");
  for (int order : {2, 3}) {
    r = test::run_zhf("product --lhs '" + z + "' --rhs '" + z + "' --order " + std::to_string(order) + " --out '" + out + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    got = test::read_json(out);
    ASSERT_EQ(got[0].size(), size_t(order * order));
    for (int i = 0; i < order * order; ++i) {
      const double expected = i == 0 ? 1 / std::sqrt(4 * kPi) : i == 6 ? 2 / std::sqrt(20 * kPi) : 0.0;
      EXPECT_NEAR(got[0][i].get<double>(), expected, kTolerance) << "order " << order << ", index " << i;
    }
  }
}

TEST(ProductCli, MismatchedInputsGetOneLineAndNoOutput) {
  const test::TempDir dir;
  const std::string a = (dir / "a.json").string(), b = (dir / "b.json").string(), big = (dir / "big.txt").string();
  const std::string out = (dir / "out.json").string();
  test::write_text(a, "[[1, 0, 0, 0], [0, 1, 0, 0]]");
  test::write_text(b, "[[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]");
  std::string line;
  for (int i = 0; i < 17 * 17; ++i) line += "1 ";
  test::write_text(big, line + "\n");
  struct Case {
    std::string args;
    int exit_code;
    std::string says;
  };
  for (const Case& c : {Case{"--lhs '" + a + "' --rhs '" + b + "'", 3, "3 vectors, where"},
                        Case{"--lhs '" + big + "' --rhs '" + a + "'", 3, "order 17 is above 16"},
                        Case{"--lhs '" + a + "' --rhs '" + a + "' --order 17", 2, "--order"},
                        Case{"--lhs '" + a + "' --rhs '" + (dir / "missing.json").string() + "'", 3, "missing.json"}}) {
    const test::RunResult r = test::run_zhf("product " + c.args + " --out '" + out + "'");
    EXPECT_EQ(r.exit_code, c.exit_code) << c.args << ": " << r.err;
    EXPECT_EQ(test::line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

}  // namespace
}  // namespace zhf
