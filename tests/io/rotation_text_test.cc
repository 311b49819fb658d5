// io/rotation_text.h: rotations as users type them, each form against the reference matrix.
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "zhf/io/errors.h"
#include "zhf/io/rotation_text.h"
#include "zhf/runtime/tolerances.h"
#include "zhf/sh/rotation_matrix.h"

namespace zhf {
namespace {

TEST(RotationText, EveryFormGivesTheReferenceMatrix) {
  const sh::Matrix3 zyz = sh::rotation_from_zyz(0.4, 1.2, -2.0);
  const auto a = io::parse_rotation("0.4, 1.2, -2.0", io::RotationForm::kZyz, "--zyz");
  const sh::Matrix3 turn = sh::rotation_about_axis(Eigen::Vector3d(1, -2, 0.5), 0.7);
  const auto b = io::parse_rotation("1 -2 0.5 0.7", io::RotationForm::kAxisAngle, "--axis-angle");
  const auto c = io::parse_rotation("0 -1 0  1 0 0  0 0 1", io::RotationForm::kMatrix, "--matrix");
  for (int i = 0; i < 9; ++i) {
    EXPECT_NEAR(a[i], zyz(i / 3, i % 3), runtime::tolerance::kExactToRounding) << "zyz entry " << i;
    EXPECT_NEAR(b[i], turn(i / 3, i % 3), runtime::tolerance::kExactToRounding) << "axis-angle entry " << i;
  }
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

}  // namespace
}  // namespace zhf
