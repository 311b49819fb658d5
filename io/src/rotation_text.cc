#include "zhf/io/rotation_text.h"

#include <cmath>
#include <vector>

#include "zhf/io/errors.h"
#include "zhf/io/numbers.h"
#include "zhf/runtime/rotation.h"

namespace zhf::io {

std::vector<double> parse_numbers(const std::string& text, std::size_t expected, const std::string& option) {
  std::vector<double> out;
  size_t i = 0;
  auto separator = [](char c) { return c == ' ' || c == ',' || c == '\t'; };
  while (i < text.size()) {
    while (i < text.size() && separator(text[i])) ++i;
    if (i == text.size()) break;
    size_t j = i;
    while (j < text.size() && !separator(text[j])) ++j;
    const std::string token = text.substr(i, j - i);
    const ParsedNumber x = parse_number(token);
    if (!x.value) throw InputError(option + ": '" + excerpt(token) + "' " + x.problem);
    out.push_back(*x.value);
    if (out.size() > expected) break;
    i = j;
  }
  if (out.size() != expected)
    throw InputError(option + ": expected " + std::to_string(expected) + " numbers, found " +
                     (out.size() > expected ? "more" : std::to_string(out.size())));
  return out;
}

ParsedRotation parse_rotation(const std::string& text, RotationForm form, const std::string& option, const EulerAxes& euler) {
  ParsedRotation out;
  switch (form) {
    case RotationForm::kMatrix:
    case RotationForm::kMatrixColumnMajor: {
      const std::vector<double> v = parse_numbers(text, 9, option);
      std::copy(v.begin(), v.end(), out.matrix.begin());
      if (form == RotationForm::kMatrixColumnMajor) out.matrix = runtime::transpose(out.matrix);
      return out;
    }
    case RotationForm::kZyz: {
      const std::vector<double> v = parse_numbers(text, 3, option);
      out.matrix = runtime::rotation_from_zyz(v[0], v[1], v[2]);
      return out;
    }
    case RotationForm::kAxisAngle: {
      const std::vector<double> v = parse_numbers(text, 4, option);
      const double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      if (!(norm > 0) || !std::isfinite(norm)) throw InputError(option + ": the axis (" + excerpt(text) + ") has no direction");
      const double u[3] = {v[0] / norm, v[1] / norm, v[2] / norm};
      out.matrix = runtime::rotation_about_unit_axis(u, v[3]);
      return out;
    }
    case RotationForm::kQuaternionWxyz:
    case RotationForm::kQuaternionXyzw: {
      const std::vector<double> v = parse_numbers(text, 4, option);
      const bool first = form == RotationForm::kQuaternionWxyz;
      const double w = first ? v[0] : v[3], x = first ? v[1] : v[0], y = first ? v[2] : v[1], z = first ? v[3] : v[2];
      if (!runtime::rotation_from_quaternion(w, x, y, z, out.matrix))
        throw InputError(option + ": the quaternion (" + excerpt(text) + ") is zero");
      out.quaternion_length = std::hypot(std::hypot(w, x), std::hypot(y, z));
      return out;
    }
    case RotationForm::kEuler: {
      const std::vector<double> v = parse_numbers(text, 3, option);
      if (!runtime::rotation_from_euler(v.data(), euler.order, euler.extrinsic, out.matrix))
        throw InputError("--euler-order: '" + excerpt(euler.order) +
                         "' is not three of X, Y, Z with no axis twice in a row (e.g. XYZ, ZYX, ZXZ)");
      return out;
    }
  }
  return out;
}

}  // namespace zhf::io
