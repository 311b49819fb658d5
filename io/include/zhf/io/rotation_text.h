// Rotations as users type them on the command line (zhf rotate), parsed to a row-major 3x3
// matrix mapping v to R v:
//   matrix:     "r00 r01 r02 r10 r11 r12 r20 r21 r22"  (9 numbers, spaces or commas)
//   zyz:        "a b g"       R = Rz(a) Ry(b) Rz(g), radians
//   axis-angle: "x y z angle" a turn by angle (radians, right-handed) about (x, y, z)
// Whether the matrix is a rotation is checked by the caller (runtime/rotation_check.h).
#pragma once

#include <array>
#include <string>

namespace zhf::io {

enum class RotationForm { kMatrix, kZyz, kAxisAngle };

// Throws InputError "<option>: ..." naming what is wrong (count, a non-number, non-finite,
// a zero axis).
std::array<double, 9> parse_rotation(const std::string& text, RotationForm form, const std::string& option);

}  // namespace zhf::io
