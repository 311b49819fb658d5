// zhf rotate: rotations typed on the command line, checked, applied to coefficient files.
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"

namespace zhf {
namespace {

namespace fs = std::filesystem;
constexpr double kDoubleTolerance = runtime::tolerance::kDouble;

TEST(RotateCli, RotatesAFileLikeTheReference) {
  const test::TempDir dir;
  std::mt19937_64 rng(4);
  sh::Normal<> normal;
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
}

TEST(RotateCli, NonRotationsAreRejectedWithTheDefectOrRepairedOnRequest) {
  const test::TempDir dir;
  const std::string in = (dir / "in.json").string(), out = (dir / "out.json").string();
  test::write_text(in, "[[1, 0.1, 0.2, 0.3]]");
  const std::string base = "rotate --coeffs '" + in + "' --out '" + out + "' ";
  const test::RunResult singular = test::run_zhf(base + "--matrix '1 0 0 0 1 0 0 0 0' --repair");
  EXPECT_EQ(singular.exit_code, 2);
  EXPECT_NE(singular.err.find("--matrix: singular; cannot repair"), std::string::npos) << singular.err;
  for (const char* defect : {"1e-3", "1e-1"}) {
    const std::string m = std::string("'1 0 0 0 1 0 0 0 ") + std::to_string(1 + std::stod(defect)) + "'";
    const test::RunResult off = test::run_zhf(base + "--matrix " + m);
    EXPECT_EQ(off.exit_code, 2) << defect;
    EXPECT_NE(off.err.find("not orthonormal: max |R R^T - I| = "), std::string::npos) << off.err;
    EXPECT_FALSE(fs::exists(out)) << defect;
    const test::RunResult repaired = test::run_zhf(base + "--matrix " + m + " --repair");
    EXPECT_EQ(repaired.exit_code, 0) << repaired.err;
    EXPECT_NE(repaired.err.find("repaired to the nearest orthogonal matrix"), std::string::npos) << repaired.err;
    fs::remove(out);
  }
  // Off by 1e-6 is within the documented tolerance (1e-5): accepted, rotated by the nearest
  // rotation (so the double result is a rotation's to double precision), and said so.
  const test::RunResult near = test::run_zhf(base + "--matrix '1 0 0 0 1 0 0 0 1.000001'");
  EXPECT_EQ(near.exit_code, 0) << near.err;
  EXPECT_NE(near.err.find("--matrix: off orthonormal by 2e-6; used the nearest orthogonal matrix"), std::string::npos) << near.err;
  const nlohmann::json got = test::read_json(out);
  const double input[4] = {1, 0.1, 0.2, 0.3};
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(got[0][i].get<double>(), input[i], kDoubleTolerance) << "index " << i;
  const test::RunResult nan = test::run_zhf(base + "--matrix '1 0 0 0 1 0 0 0 nan'");
  EXPECT_EQ(nan.exit_code, 2);
  EXPECT_NE(nan.err.find("--matrix: 'nan' is not finite"), std::string::npos) << nan.err;
  const test::RunResult two = test::run_zhf(base + "--zyz '1 2 3' --axis-angle '0 0 1 1'");
  EXPECT_EQ(two.exit_code, 2);
  EXPECT_NE(two.err.find("exactly one of --matrix, --zyz, --axis-angle, --quat, --quat-xyzw, --euler"), std::string::npos)
      << two.err;
  fs::remove(out);
  for (const auto& [options, message] : std::vector<std::pair<std::string, std::string>>{
           {"--euler '1 2 3' --intrinsic", "--euler and --euler-order go together"},
           {"--euler '1 2 3' --euler-order XYZ", "--euler: say --intrinsic or --extrinsic"},
           {"--euler '1 2 3' --euler-order XYZ --intrinsic --extrinsic", "--euler: say --intrinsic or --extrinsic"},
           {"--euler '1 2 3' --euler-order XYY --intrinsic", "--euler-order: 'XYY' is not three of X, Y, Z"},
           {"--quat '0 0 0 0'", "--quat: the quaternion (0 0 0 0) is zero"},
           {"--zyz '1 2 3' --column-major", "--column-major: applies to --matrix only"},
           {"--zyz '1 2 3' --convention y-down", "--convention: 'y-down' is not one of zhf, condon-shortley, 3dgs"},
       }) {
    const test::RunResult bad = test::run_zhf(base + options);
    EXPECT_EQ(bad.exit_code, 2) << options;
    EXPECT_NE(bad.err.find(message), std::string::npos) << options << ": " << bad.err;
    EXPECT_FALSE(fs::exists(out)) << options;
  }
}

// The same transform in every form the command takes gives the same file; a reflection and a
// convention are applied as stated.
TEST(RotateCli, EveryRotationFormReflectionsAndConventions) {
  const test::TempDir dir;
  const std::string in = (dir / "in.json").string();
  std::mt19937_64 rng(5);
  sh::Normal<> normal;
  std::vector<double> f(16);
  for (double& x : f) x = normal(rng);
  test::write_text(in, nlohmann::json::array({f}).dump());
  auto rotate = [&](const std::string& options) {
    const std::string out = (dir / "out.json").string();
    const test::RunResult r = test::run_zhf("rotate --coeffs '" + in + "' --out '" + out + "' " + options);
    EXPECT_EQ(r.exit_code, 0) << options << ": " << r.err;
    const nlohmann::json got = test::read_json(out);
    fs::remove(out);
    return got[0].get<std::vector<double>>();
  };
  auto expect_near = [](const std::vector<double>& a, const std::vector<double>& b, const std::string& what) {
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], kDoubleTolerance) << what << ", index " << i;
  };
  // A half turn about z, written five ways.
  const std::vector<double> half_turn = rotate("--axis-angle '0 0 1 3.141592653589793'");
  expect_near(rotate("--quat '0 0 0 1'"), half_turn, "--quat");
  expect_near(rotate("--quat-xyzw '0 0 2 0'"), half_turn, "--quat-xyzw");
  expect_near(rotate("--euler '0 0 3.141592653589793' --euler-order XYZ --extrinsic"), half_turn, "--euler");
  expect_near(rotate("--matrix '-1 0 0 0 -1 0 0 0 1' --column-major"), half_turn, "--matrix --column-major");
  // An intrinsic XYZ turn is the extrinsic ZYX turn with the angles reversed.
  expect_near(rotate("--euler '0.3 -0.8 1.9' --euler-order XYZ --intrinsic"),
              rotate("--euler '1.9 -0.8 0.3' --euler-order ZYX --extrinsic"), "intrinsic vs extrinsic");
  // The mirror z -> -z, an exact map: coefficient (l, m) times (-1)^(l+m), bit for bit.
  const std::vector<double> mirrored = rotate("--matrix '1 0 0 0 1 0 0 0 -1'");
  for (int l = 0; l < 4; ++l)
    for (int m = -l; m <= l; ++m) {
      const int i = l * (l + 1) + m;
      EXPECT_EQ(mirrored[i], (l + m) % 2 ? -f[i] : f[i]) << "mirror, index " << i;
    }
  // In the Condon-Shortley (and 3DGS) convention a half turn about z is still a half turn, and
  // a quarter turn is conjugated by it: the same as zhf's quarter turn on (-1)^m-signed input.
  std::vector<double> signed_f = f;
  for (int l = 0; l < 4; ++l)
    for (int m = -l; m <= l; ++m)
      if (m % 2) signed_f[l * (l + 1) + m] = -signed_f[l * (l + 1) + m];
  test::write_text(in, nlohmann::json::array({signed_f}).dump());
  std::vector<double> zhf_quarter = rotate("--axis-angle '1 2 3 0.7'");
  for (int l = 0; l < 4; ++l)
    for (int m = -l; m <= l; ++m)
      if (m % 2) zhf_quarter[l * (l + 1) + m] = -zhf_quarter[l * (l + 1) + m];
  test::write_text(in, nlohmann::json::array({f}).dump());
  expect_near(rotate("--axis-angle '1 2 3 0.7' --convention 3dgs"), zhf_quarter, "--convention 3dgs");
  expect_near(rotate("--axis-angle '1 2 3 0.7' --convention y-up-rh"), rotate("--axis-angle '1 2 3 0.7'"),
              "--convention y-up-rh (rotation and data in the same axes)");
}

}  // namespace
}  // namespace zhf
