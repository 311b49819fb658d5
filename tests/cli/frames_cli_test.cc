// zhf designs, zhf frame and zhf needlets window from the command line: byte-identical designs
// whatever the thread count, the checked-in designs reproduced, frame reports, window reports,
// bad input refused in one line.
#include <algorithm>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"
#include "test_tolerances.h"
#include "zhf/frames/designs.h"
#include "zhf/tolerances/tolerances.h"

namespace zhf {
namespace {

namespace fs = std::filesystem;

TEST(DesignsCli, SameFileWhateverTheThreadsAndAsCheckedIn) {
  const test::TempDir dir;
  for (int t : {4, 9, 13}) {
    const std::string one = (dir / "one.json").string(), two = (dir / "two.json").string();
    const std::string base = "designs --t " + std::to_string(t) + " --json ";
    const test::RunResult a = test::run_zhf(base + "'" + one + "' --threads 1");
    const test::RunResult b = test::run_zhf(base + "'" + two + "' --threads 2");
    ASSERT_EQ(a.exit_code, 0) << a.err;
    ASSERT_EQ(b.exit_code, 0) << b.err;
    EXPECT_EQ(test::read_text(one), test::read_text(two)) << "t " << t;
    EXPECT_EQ(test::read_text(one), test::read_text(frames::design_path(test::source_path("generated/designs"), t)))
        << "t " << t << ": the checked-in design is stale (bash scripts/make_designs.sh)";
  }
}

// Each symmetry asked for without --count takes its own count, where the default has another
// symmetry (at t = 12 the default is tetrahedral, 84 points): antipodal 12-designs are 13-designs,
// 94 points by symmetric_count.
TEST(DesignsCli, ASymmetryWithoutACountPicksItsOwnCount) {
  const test::TempDir dir;
  const std::string out = (dir / "d.json").string();
  const test::RunResult r = test::run_zhf("designs --t 12 --symmetric --quiet --json '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(test::read_text(out));
  EXPECT_EQ(j.at("symmetric"), true);
  EXPECT_EQ(j.at("points").size(), 94u) << r.out;
  // --symmetric with --threefold: orbits of 6 (t = 23: 276 points).
  const test::RunResult both = test::run_zhf("designs --t 23 --symmetric --threefold --quiet --json '" + out + "'");
  ASSERT_EQ(both.exit_code, 0) << both.err;
  const nlohmann::json k = nlohmann::json::parse(test::read_text(out));
  EXPECT_EQ(k.at("symmetric"), true);
  EXPECT_EQ(k.at("threefold"), true);
  EXPECT_EQ(k.at("points").size(), 276u) << both.out;
}

TEST(FrameCli, DesignsAreTightAndTablesReportTheirBands) {
  const std::string design = test::source_path("generated/designs/t_6.json");
  test::RunResult r = test::run_zhf("frame --directions '" + design + "' --bands 0..3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("tight"), std::string::npos) << r.out;
  r = test::run_zhf("frame --directions '" + design + "' --bands 0..4");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("tight"), std::string::npos) << r.out;  // 24 points, 25 functions: not even a frame
  EXPECT_NE(r.out.find("not a frame"), std::string::npos) << r.out;
  r = test::run_zhf("frame --table '" + test::source_path("generated/lobes/order_5.json") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::line_count(r.out), 4) << r.out;  // the header and bands 2, 3, 4
}

TEST(NeedletWindowCli, ReportsFrameBoundsAndLocalisationPerWindow) {
  const test::TempDir dir;
  for (const char* window : {"standard", "spline", "mexican"}) {
    const std::string out = (dir / (std::string(window) + ".json")).string();
    const test::RunResult r = test::run_zhf(std::string("needlets window --order 33 --level 3 --window ") + window + " --out '" + out + "'");
    ASSERT_EQ(r.exit_code, 0) << window << ": " << r.err;
    const nlohmann::json report = nlohmann::json::parse(test::read_text(out));
    EXPECT_EQ(report["window"], window);
    const double least = report["frame_bounds"][0], most = report["frame_bounds"][1];
    if (std::string(window) == "mexican") {
      EXPECT_GT(most / least, 1.01) << "a Mexican frame is not tight";
    } else {
      EXPECT_NEAR(least, 1.0, zhf::tolerance::kNeedletWindow) << window;
      EXPECT_NEAR(most, 1.0, zhf::tolerance::kNeedletWindow) << window;
    }
    const nlohmann::json& caps = report["localisation"]["outside"];
    ASSERT_EQ(caps.size(), 4u);
    for (std::size_t i = 1; i < caps.size(); ++i) EXPECT_LT(caps[i][1].get<double>(), caps[i - 1][1].get<double>()) << window;
  }
  const test::RunResult bad = test::run_zhf("needlets window --order 9 --window gaussian");
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("--window: 'gaussian' is not standard, spline or mexican"), std::string::npos) << bad.err;
}

TEST(FramesCli, BadInputGetsOneLineAndNoOutput) {
  const test::TempDir dir;
  const std::string zero = (dir / "zero.json").string(), out = (dir / "out.json").string();
  test::write_text(zero, "[[0, 0, 1], [0, 0, 0]]");
  struct Case {
    std::string args;
    int exit_code;
    std::string says;
  };
  for (const Case& c : {Case{"designs --t 0 --json '" + out + "'", 2, "--t"}, Case{"designs --t 101 --json '" + out + "'", 2, "--t"},
                        Case{"designs --t 3 --points 7 --symmetric --json '" + out + "'", 2, "even count"},
                        Case{"designs --t 13 --count 100 --threefold --json '" + out + "'", 2, "multiple of 3 points"},
                        Case{"designs --t 13 --threefold --tetrahedral --json '" + out + "'", 2, "not with --symmetric or --threefold"},
                        Case{"designs --t 23 --symmetric --tetrahedral --json '" + out + "'", 2, "not with --symmetric or --threefold"},
                        Case{"designs --t 23 --symmetric --threefold --count 280 --json '" + out + "'", 2, "multiple of 6 points"},
                        Case{"designs --t 12 --points 13 --starts 1 --json '" + out + "'", 1, "no 13-point 12-design"},
                        Case{"frame --directions '" + zero + "' --bands 0..1 --json '" + out + "'", 3, "[1]: not a direction"},
                        Case{"frame --directions '" + zero + "' --json '" + out + "'", 2, "--bands"},
                        Case{"frame --bands 0..2 --json '" + out + "'", 2, "--directions or --table"},
                        Case{"frame --directions '" + zero + "' --bands 0..64", 2, "--bands"}}) {
    const test::RunResult r = test::run_zhf(c.args);
    EXPECT_EQ(r.exit_code, c.exit_code) << c.args << ": " << r.err;
    EXPECT_EQ(test::line_count(r.err), 1) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

}  // namespace
}  // namespace zhf

namespace zhf {
namespace {

TEST(NeedletPrtCli, ReportsErrorsPerCoefficientCountAndRefusesBadOptions) {
  const test::TempDir dir;
  const std::string out = (dir / "prt.json").string(), csv = (dir / "prt.csv").string(), shading = (dir / "shading.csv").string();
  const test::RunResult r =
      test::run_zhf({"needlets", "prt", "--side", "2", "--order", "9", "--kept", "4,16", "--out", out, "--csv", csv, "--shading-csv", shading});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json report = test::read_json(out);
  EXPECT_EQ(report["format"], "zhf-needlet-prt-1");
  ASSERT_EQ(report["rows"].size(), 3u);
  EXPECT_LE(report["parseval_gap"].get<double>(), zhf::tolerance::kParsevalShading);
  EXPECT_EQ(test::line_count(test::read_text(csv)), 4);
  const std::string images = test::read_text(shading);
  EXPECT_EQ(test::line_count(images), 5);  // a header and 2 x 2 vertices
  // x, y, exact and 3 x (SH, needlets, SH's best K) a vertex: 11 commas a line, the header's too
  EXPECT_EQ(std::count(images.begin(), images.end(), ','), 5 * 11);
  for (const auto& [args, message] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"needlets", "prt", "--scene", "teapot"}, "--scene: 'teapot' is not open, sphere, corner or spheres"},
           {{"needlets", "prt", "--transfer", "mirror"}, "--transfer: 'mirror'"},
           {{"needlets", "prt", "--order", "9", "--kept", "2000"}, "--kept: 2000 is more than the frame's"},
           {{"needlets", "prt", "--order", "9", "--kept", "5000"}, "--kept: must be 1..4096"},  // the largest frame's size
           {{"needlets", "prt", "--side", "65"}, "--side"},
       }) {
    const test::RunResult bad = test::run_zhf(args);
    EXPECT_EQ(bad.exit_code, 2) << message << ": " << bad.err;
    EXPECT_NE(bad.err.find(message), std::string::npos) << bad.err;
  }
  // The sky image, in both spellings (--sky is the old one).
  for (const char* option : {"--image", "--sky"}) {
    const test::RunResult missing = test::run_zhf({"needlets", "prt", "--order", "5", option, (dir / "none.hdr").string(), "--out", out + "2"});
    EXPECT_EQ(missing.exit_code, 3) << option << ": " << missing.err;
    EXPECT_NE(missing.err.find("none.hdr"), std::string::npos) << option << ": " << missing.err;
    EXPECT_FALSE(std::filesystem::exists(out + "2")) << option;
  }
}

}  // namespace
}  // namespace zhf
