// io/rotation_text.h: rotations as users type them, each form against the reference matrix.
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "test_tolerances.h"

#include "zhf/io/errors.h"
#include "zhf/io/rotation_text.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/rotation_matrix.h"

namespace zhf {
namespace {

TEST(RotationText, EveryFormGivesTheReferenceMatrix) {
  const sh::RotationMatrix zyz = sh::rotation_from_zyz(0.4, 1.2, -2.0);
  const auto a = io::parse_rotation("0.4, 1.2, -2.0", io::RotationForm::kZyz, "--zyz").matrix;
  const sh::RotationMatrix turn = sh::rotation_about_axis(Eigen::Vector3d(1, -2, 0.5), 0.7);
  const auto b = io::parse_rotation("1 -2 0.5 0.7", io::RotationForm::kAxisAngle, "--axis-angle").matrix;
  const auto c = io::parse_rotation("0 -1 0  1 0 0  0 0 1", io::RotationForm::kMatrix, "--matrix").matrix;
  const auto column = io::parse_rotation("0 -1 0  1 0 0  0 0 1", io::RotationForm::kMatrixColumnMajor, "--matrix").matrix;
  // The same turn as a quaternion in both component orders (any length) and as Euler angles.
  const double half = 0.35, len = 2.5;
  const Eigen::Vector3d u = Eigen::Vector3d(1, -2, 0.5).normalized() * std::sin(half) * len;
  const std::string w = std::to_string(std::cos(half) * len);
  const std::string xyz = std::to_string(u[0]) + " " + std::to_string(u[1]) + " " + std::to_string(u[2]);
  const auto q1 = io::parse_rotation(w + " " + xyz, io::RotationForm::kQuaternionWxyz, "--quat");
  const auto q2 = io::parse_rotation(xyz + " " + w, io::RotationForm::kQuaternionXyzw, "--quat-xyzw");
  const auto e = io::parse_rotation("0.4 1.2 -2.0", io::RotationForm::kEuler, "--euler", {"ZYZ", false}).matrix;
  for (int i = 0; i < 9; ++i) {
    EXPECT_NEAR(a[i], zyz(i / 3, i % 3), zhf::tolerance::kExactToRounding) << "zyz entry " << i;
    EXPECT_NEAR(b[i], turn(i / 3, i % 3), zhf::tolerance::kExactToRounding) << "axis-angle entry " << i;
    EXPECT_NEAR(e[i], zyz(i / 3, i % 3), zhf::tolerance::kExactToRounding) << "euler entry " << i;
    // to_string keeps 6 decimals.
    EXPECT_NEAR(q1.matrix[i], turn(i / 3, i % 3), test::kSixDecimals) << "quaternion wxyz entry " << i;
    EXPECT_EQ(q1.matrix[i], q2.matrix[i]) << "quaternion xyzw entry " << i;
    EXPECT_EQ(column[i], c[3 * (i % 3) + i / 3]) << "column-major entry " << i;
  }
  EXPECT_NEAR(q1.quaternion_length, len, test::kSixDecimals);
  EXPECT_EQ(c[1], -1.0);
  EXPECT_EQ(c[3], 1.0);
}

TEST(RotationText, BadTextNamesTheOption) {
  const std::vector<std::tuple<std::string, io::RotationForm, std::string>> cases = {
      {"1 2", io::RotationForm::kZyz, "--zyz: expected 3 numbers, found 2"},
      {"1 2 x", io::RotationForm::kZyz, "--zyz: 'x' is not a number"},
      {"1 2 inf", io::RotationForm::kZyz, "--zyz: 'inf' is not finite"},
      {"1 2 ++1", io::RotationForm::kZyz, "--zyz: '++1' is not a number"},
      {"0 0 0 1", io::RotationForm::kAxisAngle, "--axis-angle: the axis (0 0 0 1) has no direction"},
      {"", io::RotationForm::kMatrix, "--matrix: expected 9 numbers, found 0"},
      {"1 2 3 4", io::RotationForm::kZyz, "--zyz: expected 3 numbers, found more"},
      {"1 2 3x", io::RotationForm::kZyz, "--zyz: '3x' is not a number"},
      {"1 2 0x10", io::RotationForm::kZyz, "--zyz: '0x10' is not a number"},
      {"1 2 nan", io::RotationForm::kZyz, "--zyz: 'nan' is not finite"},
      {"1 2 -nan", io::RotationForm::kZyz, "--zyz: '-nan' is not finite"},
      {"1 2 1e999", io::RotationForm::kZyz, "--zyz: '1e999' is beyond the range of a double"},
      {"0 0 0 0", io::RotationForm::kQuaternionWxyz, "--quat: the quaternion (0 0 0 0) is zero"},
      {"1 0 0", io::RotationForm::kQuaternionXyzw, "--quat-xyzw: expected 4 numbers, found 3"},
      {"1 2 3", io::RotationForm::kEuler, "--euler-order: 'XXZ' is not three of X, Y, Z with no axis twice in a row (e.g. XYZ, ZYX, ZXZ)"},
  };
  for (const auto& [text, form, message] : cases) {
    try {
      io::parse_rotation(text, form, message.substr(0, message.find(':')), {"XXZ", false});
      ADD_FAILURE() << "accepted '" << text << "'";
    } catch (const io::InputError& e) {
      EXPECT_EQ(std::string(e.what()), message);
    }
  }
}

}  // namespace
}  // namespace zhf
