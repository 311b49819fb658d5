// zhf rotate: rotations typed on the command line, checked, applied to coefficient files.
#include <cmath>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include "test_support.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/tolerances.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"

namespace zhf {
namespace {

namespace fs = std::filesystem;
constexpr double kDoubleTolerance = runtime::tolerance::kDouble;

TEST(RotateCli, RotatesAFileLikeTheReference) {
  const fs::path dir = test::make_temp_dir();
  std::mt19937_64 rng(4);
  std::normal_distribution<double> normal;
  for (int order : {3, 8, 10}) {
    std::vector<double> f(order * order);
    for (double& x : f) x = normal(rng);
    const std::string in = (dir / "in.json").string(), out = (dir / "out.json").string();
    test::write_text(in, nlohmann::json::array({f}).dump());
    const test::RunResult r = test::run_zhf("rotate --coeffs '" + in + "' --zyz '0.3 2.1 -0.7' --out '" + out + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json got = test::read_json(out);
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
  test::write_text(in, "[[1, 0.1, 0.2, 0.3]]");
  const std::string base = "rotate --coeffs '" + in + "' --out '" + out + "' ";
  const test::RunResult reflection = test::run_zhf(base + "--matrix '1 0 0 0 1 0 0 0 -1' --repair");
  EXPECT_EQ(reflection.exit_code, 2);
  EXPECT_NE(reflection.err.find("--matrix: rotation matrix is a reflection (det -1"), std::string::npos) << reflection.err;
  for (const char* defect : {"1e-3", "1e-1"}) {
    const std::string m = std::string("'1 0 0 0 1 0 0 0 ") + std::to_string(1 + std::stod(defect)) + "'";
    const test::RunResult off = test::run_zhf(base + "--matrix " + m);
    EXPECT_EQ(off.exit_code, 2) << defect;
    EXPECT_NE(off.err.find("not orthonormal: max |R R^T - I| = "), std::string::npos) << off.err;
    EXPECT_FALSE(fs::exists(out)) << defect;
    const test::RunResult repaired = test::run_zhf(base + "--matrix " + m + " --repair");
    EXPECT_EQ(repaired.exit_code, 0) << repaired.err;
    EXPECT_NE(repaired.err.find("repaired to the nearest rotation"), std::string::npos) << repaired.err;
    fs::remove(out);
  }
  // Off by 1e-6 is within the documented tolerance (1e-5): accepted, rotated by the nearest
  // rotation (so the double result is a rotation's to double precision), and said so.
  const test::RunResult near = test::run_zhf(base + "--matrix '1 0 0 0 1 0 0 0 1.000001'");
  EXPECT_EQ(near.exit_code, 0) << near.err;
  EXPECT_NE(near.err.find("--matrix: off orthonormal by 2e-06; rotated by the nearest rotation"), std::string::npos) << near.err;
  const nlohmann::json got = test::read_json(out);
  const double input[4] = {1, 0.1, 0.2, 0.3};
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(got[0][i].get<double>(), input[i], kDoubleTolerance) << "index " << i;
  const test::RunResult nan = test::run_zhf(base + "--matrix '1 0 0 0 1 0 0 0 nan'");
  EXPECT_EQ(nan.exit_code, 2);
  EXPECT_NE(nan.err.find("--matrix: 'nan' is not finite"), std::string::npos) << nan.err;
  const test::RunResult two = test::run_zhf(base + "--zyz '1 2 3' --axis-angle '0 0 1 1'");
  EXPECT_EQ(two.exit_code, 2);
  EXPECT_NE(two.err.find("exactly one of --matrix, --zyz, --axis-angle"), std::string::npos) << two.err;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace zhf
