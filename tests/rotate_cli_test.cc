// zhf rotate: rotations typed on the command line, checked, applied to coefficient files.
#include <cmath>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/rotation_text.h"
#include "zhf/sh/reference_rotation.h"

namespace zhf {
namespace {

namespace fs = std::filesystem;
constexpr double kDoubleTolerance = 1e-12;

TEST(RotationText, EveryFormGivesTheReferenceMatrix) {
  const sh::Matrix3 zyz = sh::rotation_from_zyz(0.4, 1.2, -2.0);
  const auto a = io::parse_rotation("0.4, 1.2, -2.0", io::RotationForm::kZyz, "--zyz");
  const sh::Matrix3 turn = sh::rotation_about_axis(Eigen::Vector3d(1, -2, 0.5), 0.7);
  const auto b = io::parse_rotation("1 -2 0.5 0.7", io::RotationForm::kAxisAngle, "--axis-angle");
  const auto c = io::parse_rotation("0 -1 0  1 0 0  0 0 1", io::RotationForm::kMatrix, "--matrix");
  for (int i = 0; i < 9; ++i) {
    EXPECT_NEAR(a[i], zyz(i / 3, i % 3), 1e-15) << "zyz entry " << i;
    EXPECT_NEAR(b[i], turn(i / 3, i % 3), 1e-15) << "axis-angle entry " << i;
  }
  EXPECT_EQ(c[1], -1.0);
  EXPECT_EQ(c[3], 1.0);
}

TEST(RotationText, BadTextNamesTheOption) {
  const std::vector<std::tuple<std::string, io::RotationForm, std::string>> cases = {
      {"1 2", io::RotationForm::kZyz, "--zyz: expected 3 numbers, found 2"},
      {"1 2 x", io::RotationForm::kZyz, "--zyz: 'x' is not a number"},
      {"1 2 inf", io::RotationForm::kZyz, "--zyz: 'inf' is not finite"},
      {"0 0 0 1", io::RotationForm::kAxisAngle, "--axis-angle: the axis (0 0 0 1) has no direction"},
      {"", io::RotationForm::kMatrix, "--matrix: expected 9 numbers, found 0"},
  };
  for (const auto& [text, form, message] : cases) {
    try {
      io::parse_rotation(text, form, message.substr(0, message.find(':')));
      ADD_FAILURE() << "accepted '" << text << "'";
    } catch (const io::InputError& e) {
      EXPECT_EQ(std::string(e.what()), message);
    }
  }
}

TEST(RotateCli, RotatesAFileLikeTheReference) {
  const fs::path dir = test::make_temp_dir();
  std::mt19937_64 rng(4);
  std::normal_distribution<double> normal;
  for (int order : {3, 8, 10}) {
    std::vector<double> f(order * order);
    for (double& x : f) x = normal(rng);
    const std::string in = (dir / "in.json").string(), out = (dir / "out.json").string();
    io::write_file_atomically(in, nlohmann::json::array({f}).dump());
    const test::RunResult r = test::run_zhf("rotate --coeffs '" + in + "' --zyz '0.3 2.1 -0.7' --out '" + out + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json got = io::read_json_file(out);
    const Eigen::VectorXd expected = sh::apply_band_matrices(
        sh::ivanic_ruedenberg(sh::rotation_from_zyz(0.3, 2.1, -0.7), order), Eigen::Map<Eigen::VectorXd>(f.data(), f.size()));
    for (int i = 0; i < order * order; ++i)
      EXPECT_NEAR(got[0][i].get<double>(), expected[i], kDoubleTolerance) << "order " << order << ", index " << i;
  }
  fs::remove_all(dir);
}

TEST(RotateCli, NonRotationsAreRejectedWithTheDefectOrRepairedOnRequest) {
  const fs::path dir = test::make_temp_dir();
  const std::string in = (dir / "in.json").string(), out = (dir / "out.json").string();
  io::write_file_atomically(in, "[[1, 0.1, 0.2, 0.3]]");
  const std::string base = "rotate --coeffs '" + in + "' --out '" + out + "' ";
  const test::RunResult reflection = test::run_zhf(base + "--matrix '1 0 0 0 1 0 0 0 -1' --repair");
  EXPECT_EQ(reflection.exit_code, 3);
  EXPECT_NE(reflection.err.find("--matrix: rotation matrix is a reflection (det -1"), std::string::npos) << reflection.err;
  for (const char* defect : {"1e-3", "1e-1"}) {
    const std::string m = std::string("'1 0 0 0 1 0 0 0 ") + std::to_string(1 + std::stod(defect)) + "'";
    const test::RunResult off = test::run_zhf(base + "--matrix " + m);
    EXPECT_EQ(off.exit_code, 3) << defect;
    EXPECT_NE(off.err.find("not orthonormal: max |R R^T - I| = "), std::string::npos) << off.err;
    EXPECT_FALSE(fs::exists(out)) << defect;
    const test::RunResult repaired = test::run_zhf(base + "--matrix " + m + " --repair");
    EXPECT_EQ(repaired.exit_code, 0) << repaired.err;
    EXPECT_NE(repaired.err.find("repaired to the nearest rotation"), std::string::npos) << repaired.err;
    fs::remove(out);
  }
  // Off by 1e-6 is rounding, within the documented tolerance (1e-5): accepted as it is.
  EXPECT_EQ(test::run_zhf(base + "--matrix '1 0 0 0 1 0 0 0 1.000001'").exit_code, 0);
  const test::RunResult nan = test::run_zhf(base + "--matrix '1 0 0 0 1 0 0 0 nan'");
  EXPECT_EQ(nan.exit_code, 3);
  EXPECT_NE(nan.err.find("--matrix: 'nan' is not finite"), std::string::npos) << nan.err;
  const test::RunResult two = test::run_zhf(base + "--zyz '1 2 3' --axis-angle '0 0 1 1'");
  EXPECT_EQ(two.exit_code, 2);
  EXPECT_NE(two.err.find("exactly one of --matrix, --zyz, --axis-angle"), std::string::npos) << two.err;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace zhf
