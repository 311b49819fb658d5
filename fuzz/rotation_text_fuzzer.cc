// The rotation parsers behind zhf rotate and zhf splat (--matrix, --column-major, --zyz,
// --axis-angle, --quat, --quat-xyzw, --euler) on arbitrary text: they may reject, never crash;
// what they accept is finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <algorithm>
#include <cstdlib>
#include <string>

#include "zhf/io/errors.h"
#include "zhf/io/rotation_text.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  using zhf::io::RotationForm;
  for (auto form : {RotationForm::kMatrix, RotationForm::kMatrixColumnMajor, RotationForm::kZyz, RotationForm::kAxisAngle,
                    RotationForm::kQuaternionWxyz, RotationForm::kQuaternionXyzw, RotationForm::kEuler}) {
    try {
      // For Euler angles the first three bytes are the axis order, the rest the angles.
      const bool euler = form == RotationForm::kEuler;
      const std::string numbers = euler ? text.substr(std::min<std::size_t>(3, size)) : text;
      const zhf::io::ParsedRotation r =
          zhf::io::parse_rotation(numbers, form, "--fuzz", {text.substr(0, 3), size % 2 == 0});
      for (double x : r.matrix)
        if (!std::isfinite(x)) std::abort();
      if (!std::isfinite(r.quaternion_length)) std::abort();
    } catch (const zhf::io::InputError&) {
    }
  }
  return 0;
}
