#include "zhf/io/rotation_text.h"

#include <cmath>
#include <vector>

#include "zhf/io/errors.h"
#include "zhf/io/numbers.h"
#include "zhf/runtime/rotation.h"

namespace zhf::io {
namespace {

// Numbers separated by spaces, tabs or commas; each token must be a whole finite number.
std::vector<double> numbers(const std::string& text, size_t expected, const std::string& option) {
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

}  // namespace

std::array<double, 9> parse_rotation(const std::string& text, RotationForm form, const std::string& option) {
  switch (form) {
    case RotationForm::kMatrix: {
      const std::vector<double> v = numbers(text, 9, option);
      std::array<double, 9> out{};
      std::copy(v.begin(), v.end(), out.begin());
      return out;
    }
    case RotationForm::kZyz: {
      const std::vector<double> v = numbers(text, 3, option);
      return runtime::rotation_from_zyz(v[0], v[1], v[2]);
    }
    case RotationForm::kAxisAngle: {
      const std::vector<double> v = numbers(text, 4, option);
      const double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      if (!(norm > 0) || !std::isfinite(norm)) throw InputError(option + ": the axis (" + excerpt(text) + ") has no direction");
      const double u[3] = {v[0] / norm, v[1] / norm, v[2] / norm};
      return runtime::rotation_about_unit_axis(u, v[3]);
    }
  }
  return {};
}

}  // namespace zhf::io
