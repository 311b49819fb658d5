// Rotations as users type them on the command line (zhf rotate), parsed to a row-major 3x3
// matrix mapping v to R v:
//   matrix:        "r00 r01 r02 r10 r11 r12 r20 r21 r22"  (9 numbers, spaces or commas)
//   column-major:  the same 9 numbers column by column (r00 r10 r20 r01 ...)
//   zyz:           "a b g"       R = Rz(a) Ry(b) Rz(g), radians
//   axis-angle:    "x y z angle" a turn by angle (radians, right-handed) about (x, y, z)
//   quaternion:    "w x y z" (scalar first) or "x y z w" (scalar last), any nonzero length
//   euler:         "a b c" radians about the axes of EulerAxes (runtime::rotation_from_euler)
// Whether the matrix is orthogonal is checked by the caller (runtime/rotation.h).
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace zhf::io {

enum class RotationForm { kMatrix, kMatrixColumnMajor, kZyz, kAxisAngle, kQuaternionWxyz, kQuaternionXyzw, kEuler };

struct EulerAxes {
  std::string order;  // "XYZ", "ZYX", "ZXZ", ...
  bool extrinsic = false;
};

struct ParsedRotation {
  std::array<double, 9> matrix{};
  double quaternion_length = 1;  // for a quaternion: its length before normalising
};

// Exactly expected numbers separated by spaces, tabs or commas (an option's text, e.g. a
// translation); throws InputError "<option>: ..." otherwise.
std::vector<double> parse_numbers(const std::string& text, std::size_t expected, const std::string& option);

// Throws InputError "<option>: ..." naming what is wrong (count, a non-number, non-finite,
// a zero axis or quaternion, an Euler order that is not one).
ParsedRotation parse_rotation(const std::string& text, RotationForm form, const std::string& option,
                              const EulerAxes& euler = {});

}  // namespace zhf::io
